#include "load_stepping.hpp"

#include "parameter_validation.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <variant>

namespace spatula::analysis {

namespace {

double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A load value for the log, independent of the stream's current format.
std::string load_text(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  return text;
}

}  // namespace

void StepParameters::declare(Teuchos::ParameterList& list, double initial, double minimum, double maximum)
{
  using parameters::Range;
  parameters::declare_double(list, "initial", initial, "first increment", Range::positive());
  parameters::declare_double(list, "minimum", minimum, "smallest increment before giving up", Range::positive());
  parameters::declare_double(list, "maximum", maximum, "largest increment", Range::positive());
  parameters::declare_int(list, "easy iterations", 4, "grow the increment after steps with at most this many "
                          "Newton iterations", Range::closed(1, 100));
  parameters::declare_double(list, "growth", 1.5, "increment growth factor", {1.0, 10.0, false, false});
  parameters::declare_double(list, "cut", 0.5, "increment factor after a failed step", {0.0, 1.0, true, true});
}

StepParameters StepParameters::from(const Teuchos::ParameterList& list, const std::string& path)
{
  StepParameters p;
  p.initial = list.get<double>("initial");
  p.minimum = list.get<double>("minimum");
  p.maximum = list.get<double>("maximum");
  p.easy_iterations = list.get<int>("easy iterations");
  p.growth = list.get<double>("growth");
  p.cut = list.get<double>("cut");
  if (p.minimum > p.initial)
    parameters::fail(parameters::key_path(path, "minimum"), p.minimum, "must not exceed 'initial' = " + std::to_string(p.initial));
  if (p.maximum < p.initial)
    parameters::fail(parameters::key_path(path, "maximum"), p.maximum, "must not be below 'initial' = " + std::to_string(p.initial));
  return p;
}

LoadPath::LoadPath(solvers::SpatulaModel& model, const solvers::NewtonSolver& newton, std::ostream* log,
                   bool convergence_tables)
    : model_(model), newton_(newton), log_(log), tables_(convergence_tables),
      x_(model.system().create_vector()), previous_(model.system().create_vector()), started_(now())
{
  auto& system = model_.system();
  system.set_control({{true, true, true}});
  points_.push_back(measure(0, -1));
  previous_->assign(*x_);
}

LoadPoint LoadPath::measure(int iterations, int negative_pivots)
{
  auto& system = model_.system();
  const auto evaluation = system.evaluate(*x_, nullptr, false);
  LoadPoint point;
  point.step = static_cast<int>(points_.size());
  point.rotation = system.master(*x_, Master::rotation);
  point.lift = system.master(*x_, Master::lift);
  point.slide = system.master(*x_, Master::slide);
  point.moment = evaluation.master_residual[0];
  point.force = evaluation.master_residual[1];
  point.slide_force = evaluation.master_residual[2];
  point.internal_energy = evaluation.internal_energy;
  point.contact_energy = evaluation.contact_energy;
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

discretization::MasterControl LoadPath::spatula_control(Master controlled, bool other_free)
{
  discretization::MasterControl control;   // all prescribed: slide (X) held
  if (controlled != Master::slide) control.prescribed[controlled == Master::rotation ? 1 : 0] = !other_free;
  return control;
}

std::optional<Failure> LoadPath::advance(Master controlled, double target, discretization::MasterControl control,
                                         const StepParameters& steps, double unit, const Callback& on_point)
{
  auto& system = model_.system();
  control.prescribed[static_cast<int>(controlled)] = true;
  system.set_control(control);
  // The rotation master is the end face's rotation from the initial inclination (theta_y - theta_s), in degrees.
  const char* name = controlled == Master::rotation ? "rotation theta_y - theta_s" : controlled == Master::lift ? "lift" : "slide";

  double value = system.master(*x_, controlled);
  double increment = steps.initial * unit;
  previous_increment_ = 0.0;   // no predictor across a change of the controlled load
  const double direction = target >= value ? 1.0 : -1.0;
  auto trial = system.create_vector();
  while (!detached_ && direction * (target - value) > 1e-12 * std::max(1.0, std::abs(target))) {
    increment = std::min(increment, direction * (target - value));
    // Secant predictor from the last two converged states (scaled to the new increment).
    trial->assign(*x_);
    if (previous_increment_ > 0.0) trial->update(increment / previous_increment_, *x_, -increment / previous_increment_, *previous_, 1.0);
    system.set_master(*trial, controlled, value + direction * increment);
    std::ostringstream table;
    const auto result = newton_.solve(*trial, tables_ ? &table : nullptr);
    if (!result.converged) {
      if (log_) *log_ << table.str() << "  step to " << name << " = " << load_text((value + direction * increment) / unit)
                      << " failed (" << result.failure << "); cutting the increment\n";
      increment *= steps.cut;
      if (increment < steps.minimum * unit * (1 - 1e-12)) {
        const double unreached = value + direction * increment / steps.cut;
        if (past_folds_ == PastFolds::jump) {   // an instability: jump at the unreached load to the far side
          if (log_) *log_ << "  " << name << " = " << load_text(unreached / unit) << ": no equilibrium near the last one "
                          << "(an instability); jumping to the next stable state\n";
          auto failure = jump(controlled, unreached, on_point);
          system.set_control(control);
          if (failure) failure->load = unreached / unit;   // in the load's unit, as every other failure
          if (failure) return failure;
          value = unreached;
          increment = steps.initial * unit;
          previous_increment_ = 0.0;
          continue;
        }
        if (past_folds_ == PastFolds::arc_length && direction > 0) {   // go round the fold, resume beyond
          if (log_) *log_ << "  " << name << " = " << load_text(unreached / unit) << " not reachable on this branch: arc-length "
                          << "continuation round the fold\n";
          auto failure = arc_length(controlled, unreached, control, *arc_length_, unit,
                                    [&](const LoadPoint& p, const Vector& x) {
            if (detachment_test_ && detachment_test_(p)) detached_ = true;
            if (on_point) on_point(p, x);
          });
          system.set_control(control);
          if (failure && !detached_) return failure;
          value = system.master(*x_, controlled);
          increment = steps.initial * unit;
          previous_increment_ = 0.0;
          continue;
        }
        Failure failure;
        failure.step = static_cast<int>(points_.size());
        failure.load = unreached / unit;
        failure.smallest_increment = increment / steps.cut / unit;
        failure.reason = result.failure;
        return failure;
      }
      previous_increment_ = 0.0;   // no predictor after a failure
      continue;
    }
    previous_->assign(*x_);
    x_->assign(*trial);
    previous_increment_ = increment;
    value += direction * increment;
    const int iterations = result.iterations.empty() ? 0 : result.iterations.back().iteration;
    const int pivots = result.iterations.empty() ? -1 : result.iterations.back().negative_pivots;
    points_.push_back(measure(iterations, pivots));
    if (log_ && tables_) *log_ << table.str();
    if (detachment_test_ && detachment_test_(points_.back())) detached_ = true;
    if (on_point) on_point(points_.back(), *x_);
    if (iterations <= steps.easy_iterations) increment = std::min(increment * steps.growth, steps.maximum * unit);
  }
  return std::nullopt;
}

void LoadPath::accept(const Vector& x, int iterations, int negative_pivots, const Callback& on_point)
{
  previous_->assign(*x_);
  x_->assign(x);
  previous_increment_ = 0.0;
  points_.push_back(measure(iterations, negative_pivots));
  if (on_point) on_point(points_.back(), *x_);
}

std::optional<Failure> LoadPath::equilibrate(const Vector& guess, discretization::MasterControl control)
{
  model_.system().set_control(control);
  auto x = model_.system().create_vector();
  x->assign(guess);
  const auto outcome = descend(*x);   // robust from a far guess: energy descent, then Newton
  if (const auto* reason = std::get_if<std::string>(&outcome)) {
    Failure failure;
    failure.reason = "no equilibrium from the initial guess: " + *reason;
    return failure;
  }
  LoadPoint start;
  start.newton_iterations = std::get<int>(outcome);
  restart(*x, start);
  return std::nullopt;
}

void LoadPath::restart(const Vector& x, const LoadPoint& point)
{
  x_->assign(x);
  previous_->assign(x);
  previous_increment_ = 0.0;
  points_.clear();
  auto measured = measure(point.newton_iterations, point.negative_pivots);
  measured.step = point.step;
  measured.external_work = point.external_work;
  measured.dissipated = point.dissipated;
  points_.push_back(measured);
}

// Minimizes Pi at the current load from x (shifted Newton + expanding line search on Pi), then confirms with plain
// Newton. Returns the iterations used, or the reason it failed.
std::variant<int, std::string> LoadPath::descend(Vector& x)
{
  auto& system = model_.system();
  auto f = system.create_vector(), direction = system.create_vector(), trial = system.create_vector();
  solvers::MumpsSolver mumps(system.owned_map(), solvers::MumpsParameters{});
  auto energy_at = [&](const Vector& state, bool& admissible) {
    const auto evaluation = system.evaluate(state, nullptr, false);
    admissible = evaluation.admissible;
    return evaluation.internal_energy + evaluation.contact_energy;
  };
  double eta = 0.0, scale = 0.0;
  int iteration = 0;
  for (; iteration < jump_.maximum_iterations; ++iteration) {
    system.set_damping(eta, Teuchos::rcpFromRef(x));   // anchored at x: a pure shift of the tangent, f unchanged
    const auto evaluation = system.evaluate(x, f.get(), true);
    system.set_damping(0.0, Teuchos::null);
    if (!evaluation.admissible) return std::string("an element inverted during the energy descent");
    if (scale == 0.0) scale = system.mean_diagonal();
    int negative = 0;
    try {
      mumps.factor(*system.jacobian());
      negative = mumps.statistics().negative_pivots;
    } catch (const std::exception&) {
      negative = 1;   // singular: treat like indefinite
    }
    if (negative > 0) {   // not a descent direction yet: shift more
      eta = eta == 0.0 ? 1e-6 * scale : jump_.shift_growth * eta;
      continue;
    }
    const double residual = f->norm2();
    // Near a stable minimum (positive definite tangent, small gradient): plain Newton finishes below. The energy
    // alone cannot resolve the last digits (its changes fall below its rounding), the gradient can.
    if (eta == 0.0 && residual < 1e-3) break;
    mumps.apply(*f, *direction);
    direction->scale(-1.0);
    const double slope = f->dot(*direction);
    bool admissible = true;
    const double energy = evaluation.internal_energy + evaluation.contact_energy;
    // Line search on Pi with expansion.
    double step = 1.0, best_step = 0.0, best_energy = energy;
    for (int trial_count = 0; trial_count < 30; ++trial_count) {
      trial->update(1.0, x, step, *direction, 0.0);
      const double value_at = energy_at(*trial, admissible);
      const bool sufficient = admissible && value_at <= energy + 1e-4 * step * slope;
      if (sufficient && value_at < best_energy) {
        best_energy = value_at;
        best_step = step;
        if (step >= 1.0 && step < 64.0) {   // still descending: try further
          step *= 2.0;
          continue;
        }
        break;
      }
      if (best_step > 0.0) break;   // the expansion went too far: keep the best
      step *= 0.5;
    }
    if (best_step == 0.0 && eta == 0.0) break;   // a plain Newton step and no measurable decrease: let Newton finish
    if (best_step == 0.0) {   // no decrease along this direction: stiffen the shift
      eta = eta == 0.0 ? 1e-6 * scale : jump_.shift_growth * eta;
      continue;
    }
    x.update(best_step, *direction, 1.0);
    eta = best_step >= 1.0 ? 0.25 * eta : 2.0 * eta;
    if (eta < 1e-9 * scale) eta = 0.0;
  }
  if (iteration >= jump_.maximum_iterations)
    return "no stable state within " + std::to_string(jump_.maximum_iterations) + " iterations";
  const auto plain = newton_.solve(x, nullptr);
  if (!plain.converged) return "Newton did not confirm the state the energy descent reached (" + plain.failure + ")";
  return iteration + (plain.iterations.empty() ? 0 : plain.iterations.back().iteration);
}

std::optional<Failure> LoadPath::jump(Master controlled, double value, const Callback& on_point)
{
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: jump past instability"));
  auto& system = model_.system();
  const auto before = points_.back();
  auto x = system.create_vector();
  x->assign(*x_);
  system.set_master(*x, controlled, value);
  const auto outcome = descend(*x);
  if (const auto* reason = std::get_if<std::string>(&outcome)) {
    Failure failure;
    failure.step = static_cast<int>(points_.size());
    failure.load = value;
    failure.reason = "jump past the instability failed: " + *reason;
    return failure;
  }
  const int iterations = std::get<int>(outcome);
  accept(*x, iterations, -1, {});
  auto& after = points_.back();
  after.after_jump = true;
  after.released = (before.internal_energy + before.contact_energy) - (after.internal_energy + after.contact_energy) +
                   (after.external_work - before.external_work);
  after.dissipated += after.released;
  if (log_)
    *log_ << "  jumped in " << iterations << " iterations (energy descent, then Newton), released "
          << load_text(2.0 * after.released) << " nN nm (full spatula)\n";
  if (detachment_test_ && detachment_test_(after)) detached_ = true;
  if (on_point) on_point(after, *x_);
  return std::nullopt;
}

}  // namespace spatula::analysis
