#include "analysis/load_history.hpp"
#include "analysis/load_path_log.hpp"

namespace spatula::analysis {

using discretization::Master;

void mark_jump(LoadPoint& point, double released)
{
  point.after_jump = true;
  point.released = released;
  point.dissipated += released;
}

LoadHistory::LoadHistory() : started_(now()) {}

LoadPoint LoadHistory::measure(discretization::DiscreteSystem& system, const discretization::Vector& x,
                               int iterations, int negative_pivots) const
{
  const auto evaluation = system.evaluate(x, nullptr, false);
  LoadPoint point;
  point.step = next_step();
  point.rotation = system.master(x, Master::rotation);
  point.lift = system.master(x, Master::lift);
  point.slide = system.master(x, Master::slide);
  point.moment = evaluation.master_residual[0];
  point.force = evaluation.master_residual[1];
  point.slide_force = evaluation.master_residual[2];
  point.internal_energy = evaluation.internal_energy;
  point.contact_energy = evaluation.contact_energy;
  point.sliding = evaluation.contact_dissipated;
  point.active_faces = evaluation.active_contact_faces;
  point.skipped_faces = evaluation.skipped_contact_faces;
  point.newton_iterations = iterations;
  point.negative_pivots = negative_pivots;
  point.seconds = now() - started_;
  if (!points_.empty()) {
    const auto& last = points_.back();
    point.dissipated = last.dissipated;
    point.external_work = last.external_work + 0.5 * (last.moment + point.moment) * (point.rotation - last.rotation) +
                          0.5 * (last.force + point.force) * (point.lift - last.lift) +
                          0.5 * (last.slide_force + point.slide_force) * (point.slide - last.slide);
  }
  return point;
}

double LoadHistory::released_energy(const LoadPoint& point) const
{
  const auto& last = points_.back();
  return (point.external_work - last.external_work) -
         (point.internal_energy + point.contact_energy - last.internal_energy - last.contact_energy);
}

void LoadHistory::restart(LoadPoint point, const LoadPoint& carried)
{
  points_.clear();
  step_offset_ = carried.step;
  if (carried.seconds > 0.0) started_ = now() - carried.seconds;   // a resumed run's clock goes on
  point.step = carried.step;
  point.seconds = now() - started_;
  point.external_work = carried.external_work;
  point.dissipated = carried.dissipated;
  points_.push_back(point);
}

double LoadHistory::elapsed_seconds() const { return now() - started_; }

}  // namespace spatula::analysis
