#include "analysis/load_stepping.hpp"
#include "analysis/instability_policy.hpp"
#include "analysis/load_path_log.hpp"

#include "parameters/parameter_validation.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <variant>

namespace spatula::analysis {

LoadPath::LoadPath(solvers::SpatulaModel& model, const solvers::EquilibriumSolver& equilibrium, std::ostream* log,
                   bool convergence_tables)
    : model_(model), equilibrium_(equilibrium), log_(log), tables_(convergence_tables),
      x_(model.system().create_vector()), previous_(model.system().create_vector()),
      older_(model.system().create_vector()),
      minimizer_(model, equilibrium, log, convergence_tables)
{
  auto& system = model_.system();
  system.set_control({{true, true, true}});   // (no factors yet)
  history_.append(measure(*x_, 0, -1));
  previous_->assign(*x_);
}

// The state of one advance(): where the path is, the next increment, and what the failed attempts since the last
// converged state say.
struct LoadPath::Stepping {
  Master controlled;
  bool force;                              // the dead load on it is the load, not its value
  const char* name;                        // of the controlled load, for the log
  discretization::MasterControl control;   // which masters are prescribed, and the dead loads
  const StepParameters& steps;
  double unit, direction, smallest;   // smallest: the minimum increment (less a rounding margin)
  double value, increment;            // the load reached and the next increment
  FailedLoad failed;
  int failures = 0;       // failed attempts in a row from the current converged state
  bool refused = false;   // an early descent was refused at refused_load, not yet passed
  double refused_load = 0.0;
};

std::optional<Failure> LoadPath::advance(Master controlled, double target, discretization::MasterControl control,
                                         const StepParameters& steps, double unit, const Callback& on_point)
{
  control.prescribed[static_cast<int>(controlled)] = true;
  set_control(control);
  return follow(controlled, false, model_.system().master(*x_, controlled), target, control, steps, unit, on_point);
}

std::optional<Failure> LoadPath::advance_force(Master loaded, double target, discretization::MasterControl control,
                                               const StepParameters& steps, double unit, const Callback& on_point)
{
  const int m = static_cast<int>(loaded);
  const double value = last().reaction(loaded);
  control.prescribed[m] = false;
  control.applied[m] = value;   // the load the face carries: no jump as the stage begins
  set_control(control);
  return follow(loaded, true, value, target, control, steps, unit, on_point);
}

std::optional<Failure> LoadPath::follow(Master controlled, bool force, double value, double target,
                                        const discretization::MasterControl& control, const StepParameters& steps,
                                        double unit, const Callback& on_point)
{
  const double direction = target >= value ? 1.0 : -1.0;
  Stepping stepping{controlled, force, load_name(controlled, force), control, steps, unit, direction,
                    steps.minimum * unit * (1 - 1e-12), value, steps.initial * unit,
                    FailedLoad(direction, steps.minimum * unit, steps.cut)};
  auto& system = model_.system();
  previous_increment_ = older_increment_ = 0.0;   // no predictor across a change of the controlled load
  ended_ = false;
  curve_.start(steps.curve_tolerance, steps.initial * unit);
  if (resumed_control_) {   // a resumed run goes on where the stopped one was
    if (resumed_control_->increment > 0.0) stepping.increment = resumed_control_->increment;
    stepping.failed.restore(*resumed_control_);
    curve_.restore(*resumed_control_);
    resumed_control_.reset();
  }
  if (resumed_jump_) {   // a checkpointed jump first: it began at this state
    const bool here = !stepping.force && resumed_jump_->controlled == controlled && jumps() &&
                      direction * (target - resumed_jump_->value) >= -1e-12 * std::max(1.0, std::abs(target));
    if (here) {
      if (auto failure = finish_resumed_jump(controlled, unit, on_point)) return failure;
      set_control(control);
      stepping.value = system.master(*x_, controlled);
      stepping.failed.forget();
      stepping.increment = steps.initial * unit;
    } else {   // another load path from this state (another master, target or way past folds): it starts afresh
      if (log_)
        *log_ << "  the checkpoint's jump is not on this load path (another load, a target short of it, or "
              << "instabilities not passed by jumps): dropped; the path starts from the last converged state\n";
      resumed_jump_.reset();
    }
  }
  auto trial = system.create_vector();
  while (!detached_ && !ended_ && direction * (target - stepping.value) > 1e-12 * std::max(1.0, std::abs(target))) {
    stepping.increment =
        stepping.failed.limit(std::min(stepping.increment, direction * (target - stepping.value)), stepping.value);
    const double load = stepping.value + direction * stepping.increment;
    predict(*trial, stepping.increment, steps.predictor);
    set_load(stepping, *trial, load);
    std::ostringstream table;
    const auto result = equilibrium_.solve(*trial, tables_ ? &table : nullptr, stepping.failed.known());
    if (!result.converged) {
      if (auto failure = after_failed_attempt(stepping, load, *trial, result.failure, table.str(), on_point))
        return failure;
      continue;
    }
    const int iterations = result.iterations.empty() ? 0 : result.iterations.back().iteration;
    const int pivots = result.iterations.empty() ? -1 : result.iterations.back().negative_pivots;
    auto point = measure(*trial, iterations, pivots);
    const auto snap = crossed_snap(stepping, load, point, table.str());
    if (const auto* failure = std::get_if<Failure>(&snap)) return *failure;
    if (std::get<bool>(snap)) continue;   // cut back: the step is tried again, shorter
    take_converged_step(stepping, *trial, point, iterations, table.str(), on_point);
  }
  return std::nullopt;
}

std::optional<Failure> LoadPath::after_failed_attempt(Stepping& stepping, double load, Vector& trial,
                                                      const std::string& newton_failure, const std::string& table,
                                                      const Callback& on_point)
{
  if (log_)
    *log_ << table << "  step to " << stepping.name << " = " << load_text(load / stepping.unit) << " failed ("
          << newton_failure << ")";
  ++stepping.failures;
  // Not where the cut leaves the smallest increment: the jump there descends from the same state anyway.
  const bool descend = !stepping.force && !stepping.refused && jump_.descend_after_failures > 0 &&
                       stepping.failures >= jump_.descend_after_failures && jumps() &&
                       jump_.step_balance_tolerance > 0.0 &&
                       stepping.increment * stepping.steps.cut >= stepping.smallest;
  if (descend) {
    if (log_) *log_ << "; energy descent at this load\n";
    if (auto point = descend_early(stepping.controlled, load, trial)) {   // an ordinary step after all
      stepping.value = load;
      stepping.failed.reached(stepping.value);
      stepping.failures = 0;
      point->step_control.increment = stepping.increment;
      stepping.failed.save(point->step_control);
      take_step(trial, *point, stepping.increment, "", on_point);
      return std::nullopt;
    }
    stepping.refused = true;   // a snap proper ahead (or no state the descent could confirm): bisect towards it
    stepping.refused_load = load;
  }
  if (log_) *log_ << (descend ? "  " : "; ") << "cutting the increment\n";
  stepping.failed.failed(load);
  stepping.increment *= stepping.steps.cut;
  if (stepping.increment < stepping.smallest) {   // no equilibrium near the last one: past the fold, or stop
    const double unreached = stepping.value + stepping.direction * stepping.increment / stepping.steps.cut;
    if (stepping.force) {   // a limit point under a dead load: no state beyond it holds the load
      Failure failure;
      failure.step = next_step();
      failure.load = unreached / stepping.unit;
      failure.smallest_increment = stepping.increment / stepping.steps.cut / stepping.unit;
      failure.reason = "no equilibrium at a larger " + std::string(stepping.name) + " (" + newton_failure +
                       "): the largest the face carries on this branch is " + load_text(stepping.value / stepping.unit);
      failure.largest_force = true;
      return failure;
    }
    auto beyond = pass_fold(stepping.controlled, unreached, stepping.control, stepping.direction,
                            stepping.increment / stepping.steps.cut, stepping.unit, newton_failure, on_point);
    if (auto* failure = std::get_if<Failure>(&beyond)) return *failure;
    stepping.value = std::get<double>(beyond);
    stepping.failed.forget();
    stepping.failures = 0;
    stepping.refused = false;
    // on a new branch: accept() has started the predictor afresh
    stepping.increment = stepping.steps.initial * stepping.unit;
  }
  if (!stepping.steps.predict_after_failure) previous_increment_ = older_increment_ = 0.0;
  return std::nullopt;
}

std::variant<bool, Failure> LoadPath::crossed_snap(Stepping& stepping, double load, LoadPoint& point,
                                                   const std::string& table)
{
  // The energy the step released: near zero on a smooth path; large when Newton crossed a snap within the step
  // and landed on another branch.
  const double released = history_.released_energy(point);
  if (!(jump_.step_balance_tolerance > 0.0 && std::abs(released) > jump_.step_balance_tolerance)) return false;
  if (stepping.increment * stepping.steps.cut >= stepping.smallest) {
    if (log_)
      *log_ << table << "  step to " << stepping.name << " = " << load_text(load / stepping.unit)
            << " converged on another branch (the step released " << released_text(released)
            << ", " << report_of_ << "): a snap within the step; cutting the increment\n";
    stepping.failed.failed(load);
    stepping.increment *= stepping.steps.cut;
    if (!stepping.steps.predict_after_failure) previous_increment_ = older_increment_ = 0.0;
    return true;
  }
  if (!policy_ || !policy_->counts_snaps_as_jumps()) {
    Failure failure;
    failure.step = next_step();
    failure.load = load / stepping.unit;
    failure.smallest_increment = stepping.increment / stepping.unit;
    failure.reason = "a snap within the smallest step (it released " + released_text(released) + ", " +
                     report_of_ + ") and instabilities are set to stop";
    return failure;
  }
  mark_jump(point, released);   // the smallest step still crosses the snap: it is the jump
  if (log_)
    *log_ << "  snap within the smallest step to " << stepping.name << " = " << load_text(load / stepping.unit)
          << ": counted as a jump, released " << released_text(released) << " (" << report_of_ << ")\n";
  return false;
}

void LoadPath::take_converged_step(Stepping& stepping, const Vector& trial, LoadPoint& point, int iterations,
                                   const std::string& table, const Callback& on_point)
{
  const double taken = stepping.increment;
  stepping.value += stepping.direction * stepping.increment;
  stepping.failed.reached(stepping.value);
  stepping.failures = 0;
  if (stepping.refused && stepping.direction * (stepping.value - stepping.refused_load) >=
                              -1e-12 * std::max(1.0, std::abs(stepping.refused_load)))
    stepping.refused = false;
  if (iterations <= stepping.steps.easy_iterations)
    stepping.increment = std::min(stepping.increment * stepping.steps.growth, stepping.steps.maximum * stepping.unit);
  if (!stepping.force) {   // the reaction curve along the load (a force stage's load is its reaction)
    curve_.reached(point.step, last().step, point.after_jump, stepping.value, point.reaction(stepping.controlled));
    stepping.increment = curve_.limit(stepping.increment);
  }
  point.step_control.increment = stepping.increment;
  stepping.failed.save(point.step_control);
  curve_.save(point.step_control);
  take_step(trial, point, taken, table, on_point);
}

const char* LoadPath::load_name(Master controlled, bool force)
{
  // The rotation master is the end face's rotation from the initial inclination (theta_y - theta_s).
  if (force) return controlled == Master::rotation ? "moment" : controlled == Master::lift ? "lift force" : "slide force";
  return controlled == Master::rotation ? "rotation theta_y - theta_s" : controlled == Master::lift ? "lift" : "slide";
}

void LoadPath::predict(Vector& trial, double increment, StepParameters::Predictor predictor) const
{
  const auto w = predictor_weights(predictor, increment, previous_increment_, older_increment_);
  trial.update(w.previous, *previous_, w.older, *older_, 0.0);
  trial.update(w.current, *x_, 1.0);
}

void LoadPath::check_end(const LoadPoint& point)
{
  if (detachment_test_ && detachment_test_(point)) detached_ = true;
  if (end_test_ && end_test_(point)) ended_ = true;
}

void LoadPath::set_control(const discretization::MasterControl& control) const
{
  auto& system = model_.system();
  if (system.control().prescribed != control.prescribed) equilibrium_.linear_solver().renew_factors();
  system.set_control(control);
}

void LoadPath::set_load(Stepping& stepping, Vector& trial, double load) const
{
  if (!stepping.force) {
    model_.system().set_master(trial, stepping.controlled, load);
    return;
  }
  stepping.control.applied[static_cast<int>(stepping.controlled)] = load;
  set_control(stepping.control);
}

std::variant<double, Failure> LoadPath::pass_fold(Master controlled, double unreached,
                                                  const discretization::MasterControl& control, double direction,
                                                  double smallest_increment, double unit,
                                                  const std::string& newton_failure, const Callback& on_point)
{
  if (policy_)
    if (auto passed = policy_->pass(*this, Fold{controlled, unreached, control, direction, unit}, on_point))
      return *passed;
  Failure failure;
  failure.step = next_step();
  failure.load = unreached / unit;
  failure.smallest_increment = smallest_increment / unit;
  failure.reason = newton_failure;
  return failure;
}

bool LoadPath::jumps() const { return policy_ && policy_->jumps(); }

std::variant<double, Failure> LoadPath::continue_past(const Fold& fold, const ArcLengthParameters& parameters,
                                                      const Callback& on_point)
{
  auto& system = model_.system();
  if (log_)
    *log_ << "  " << load_name(fold.controlled) << " = " << load_text(fold.unreached / fold.unit)
          << " not reachable on this branch: arc-length continuation round the fold\n";
  auto failure = arc_length(fold.controlled, fold.unreached, fold.control, parameters, fold.unit,
                            [&](const LoadPoint& p, const Vector& x) {
                              check_end(p);
                              if (on_point) on_point(p, x);
                            });
  set_control(fold.control);
  if (failure && !detached_) return *failure;
  return system.master(*x_, fold.controlled);
}

void LoadPath::take_step(const Vector& state, const LoadPoint& point, double increment, const std::string& table,
                         const Callback& on_point)
{
  older_->assign(*previous_);
  older_increment_ = previous_increment_;
  previous_->assign(*x_);
  x_->assign(state);
  previous_increment_ = increment;
  history_.append(committed(point));
  if (log_ && tables_) *log_ << table;
  check_end(last());
  if (on_point) on_point(last(), *x_);
}

LoadPoint LoadPath::committed(const LoadPoint& point)
{
  if (!model_.system().commit_contact_history(*x_)) return point;
  const auto after = measure(*x_, point.newton_iterations, point.negative_pivots);
  LoadPoint result = point;
  result.internal_energy = after.internal_energy;
  result.contact_energy = after.contact_energy;
  result.sliding = after.sliding;
  return result;
}

void LoadPath::accept(const Vector& x, int iterations, int negative_pivots, const Callback& on_point)
{
  previous_->assign(*x_);
  x_->assign(x);
  previous_increment_ = older_increment_ = 0.0;
  history_.append(committed(measure(*x_, iterations, negative_pivots)));
  if (on_point) on_point(last(), *x_);
}

std::optional<Failure> LoadPath::equilibrate(const Vector& guess, discretization::MasterControl control)
{
  set_control(control);
  auto x = model_.system().create_vector();
  x->assign(guess);
  const auto outcome = minimizer_.minimize(*x);   // robust from a far guess: energy descent, then Newton
  if (!outcome.found) {
    Failure failure;
    failure.reason = "no equilibrium from the initial guess: " + outcome.failure;
    return failure;
  }
  LoadPoint start;
  start.newton_iterations = outcome.iterations;
  restart(*x, start);
  return std::nullopt;
}

void LoadPath::restart(const Vector& x, const LoadPoint& point, bool resume_step_control)
{
  x_->assign(x);
  previous_->assign(x);
  previous_increment_ = older_increment_ = 0.0;
  jump_in_progress_.reset();   // (resume_jump() after this sets the one to go on with)
  resumed_jump_.reset();
  if (resume_step_control) resumed_control_ = point.step_control;
  else resumed_control_.reset();
  history_.restart(measure(*x_, point.newton_iterations, point.negative_pivots), point);
}

}  // namespace spatula::analysis
