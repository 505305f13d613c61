#include "analysis/load_stepping.hpp"

#include "parameters/parameter_validation.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
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

FailedLoad::FailedLoad(double direction, double smallest, double cut)
  : direction_(direction), smallest_(smallest), cut_(cut)
{
}

void FailedLoad::failed(double load)
{
  if (known_ && direction_ * (load - load_) >= -tolerance(load)) {
    bisecting_ = true;   // the same load (or one beyond it) failed again
  } else {
    load_ = load;
    known_ = true;
  }
}

void FailedLoad::reached(double value)
{
  if (known_ && direction_ * (load_ - value) <= tolerance(value)) forget();
}

void FailedLoad::forget()
{
  known_ = bisecting_ = false;
}

double FailedLoad::limit(double increment, double value) const
{
  if (!bisecting_) return increment;
  const double gap = direction_ * (load_ - value);
  return gap * cut_ >= smallest_ * (1 - 1e-12) ? std::min(increment, gap * cut_) : gap;
}

void FailedLoad::save(StepControllerState& state) const
{
  state.failed_load = load_;
  state.failed_known = known_;
  state.bisecting = bisecting_;
}

void FailedLoad::restore(const StepControllerState& state)
{
  load_ = state.failed_load;
  known_ = state.failed_known;
  bisecting_ = state.bisecting;
}

double FailedLoad::tolerance(double value)
{
  return 1e-12 * std::max(1.0, std::abs(value));
}

const std::vector<std::string>& StepParameters::predictor_names()
{
  static const std::vector<std::string> names = {"secant", "quadratic"};
  return names;
}

void StepParameters::declare(Teuchos::ParameterList& list, const StepParameters& d)
{
  using parameters::Range;
  parameters::declare_double(list, "initial", d.initial, "first increment", Range::positive());
  parameters::declare_double(list, "minimum", d.minimum, "smallest increment before giving up", Range::positive());
  parameters::declare_double(list, "maximum", d.maximum, "largest increment", Range::positive());
  parameters::declare_int(list, "easy iterations", d.easy_iterations, "grow the increment after steps with at most "
                          "this many Newton iterations", Range::closed(1, 100));
  parameters::declare_double(list, "growth", d.growth, "increment growth factor", {1.0, 10.0, false, false});
  parameters::declare_double(list, "cut", d.cut, "increment factor after a failed step", {0.0, 1.0, true, true});
  parameters::declare_string(list, "predictor", parameters::name_of(d.predictor, predictor_names()),
                             "the trial state of a step: extrapolated from the last two converged states (secant) or "
                             "the last three (quadratic in the load)", predictor_names());
  parameters::declare_bool(list, "predict after a failure", d.predict_after_failure,
                           "a retry with a shorter increment after a failed attempt starts from the predictor "
                           "(true) or from the last converged state with only the load moved (false)");
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
  p.predictor = parameters::choice<Predictor>(list, "predictor", predictor_names());
  p.predict_after_failure = list.get<bool>("predict after a failure");
  if (p.minimum > p.initial)
    parameters::fail(parameters::key_path(path, "minimum"), p.minimum, "must not exceed 'initial' = " + std::to_string(p.initial));
  if (p.maximum < p.initial)
    parameters::fail(parameters::key_path(path, "maximum"), p.maximum, "must not be below 'initial' = " + std::to_string(p.initial));
  return p;
}

LoadPath::LoadPath(solvers::SpatulaModel& model, const solvers::NewtonSolver& newton, std::ostream* log,
                   bool convergence_tables)
    : model_(model), newton_(newton), log_(log), tables_(convergence_tables),
      x_(model.system().create_vector()), previous_(model.system().create_vector()),
      older_(model.system().create_vector()), started_(now())
{
  auto& system = model_.system();
  system.set_control({{true, true, true}});
  points_.push_back(measure(*x_, 0, -1));
  previous_->assign(*x_);
}

LoadPoint LoadPath::measure(const Vector& x, int iterations, int negative_pivots) const
{
  auto& system = model_.system();
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

// The state of one advance(): where the path is, the next increment, and what the failed attempts since the last
// converged state say.
struct LoadPath::Stepping {
  Master controlled;
  const char* name;                        // of the controlled load, for the log
  discretization::MasterControl control;   // which masters are prescribed
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
  auto& system = model_.system();
  control.prescribed[static_cast<int>(controlled)] = true;
  system.set_control(control);
  const double value = system.master(*x_, controlled);
  const double direction = target >= value ? 1.0 : -1.0;
  const double smallest = steps.minimum * unit * (1 - 1e-12);
  Stepping stepping{controlled, load_name(controlled), control, steps, unit, direction, smallest, value,
                    steps.initial * unit, FailedLoad(direction, steps.minimum * unit, steps.cut)};
  previous_increment_ = older_increment_ = 0.0;   // no predictor across a change of the controlled load
  if (resumed_control_) {   // a resumed run goes on where the stopped one was
    if (resumed_control_->increment > 0.0) stepping.increment = resumed_control_->increment;
    stepping.failed.restore(*resumed_control_);
    resumed_control_.reset();
  }
  if (resumed_jump_) {   // a checkpointed jump first: it began at this state
    const bool here = resumed_jump_->controlled == controlled && past_folds_ == PastFolds::jump &&
                      direction * (target - resumed_jump_->value) >= -1e-12 * std::max(1.0, std::abs(target));
    if (here) {
      if (auto failure = finish_resumed_jump(controlled, unit, on_point)) return failure;
      system.set_control(control);
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
  while (!detached_ && direction * (target - stepping.value) > 1e-12 * std::max(1.0, std::abs(target))) {
    stepping.increment =
        stepping.failed.limit(std::min(stepping.increment, direction * (target - stepping.value)), stepping.value);
    const double load = stepping.value + direction * stepping.increment;
    predict(*trial, controlled, load, stepping.increment, steps.predictor);
    std::ostringstream table;
    const auto result = newton_.solve(*trial, tables_ ? &table : nullptr, stepping.failed.known());
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

std::optional<Failure> LoadPath::finish_resumed_jump(Master controlled, double unit, const Callback& on_point)
{
  const auto jump_state = std::move(*resumed_jump_);
  resumed_jump_.reset();
  if (log_)
    *log_ << "  " << load_name(controlled) << " = " << load_text(jump_state.value / unit)
          << ": going on with the jump's energy descent from its checkpoint (iteration " << jump_state.iterations
          << ")" << std::endl;
  auto failure = jump(controlled, jump_state.value, on_point, &jump_state);
  if (failure) failure->load = jump_state.value / unit;   // in the load's unit, as every other failure
  return failure;
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
  const bool descend = !stepping.refused && jump_.descend_after_failures > 0 &&
                       stepping.failures >= jump_.descend_after_failures && past_folds_ == PastFolds::jump &&
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
  const double released = released_energy(point);
  if (!(jump_.step_balance_tolerance > 0.0 && std::abs(released) > jump_.step_balance_tolerance)) return false;
  if (stepping.increment * stepping.steps.cut >= stepping.smallest) {
    if (log_)
      *log_ << table << "  step to " << stepping.name << " = " << load_text(load / stepping.unit)
            << " converged on another branch (the step released " << load_text(2.0 * released)
            << " nN nm, full spatula): a snap within the step; cutting the increment\n";
    stepping.failed.failed(load);
    stepping.increment *= stepping.steps.cut;
    if (!stepping.steps.predict_after_failure) previous_increment_ = older_increment_ = 0.0;
    return true;
  }
  if (past_folds_ == PastFolds::stop) {
    Failure failure;
    failure.step = next_step();
    failure.load = load / stepping.unit;
    failure.smallest_increment = stepping.increment / stepping.unit;
    failure.reason = "a snap within the smallest step (it released " + load_text(2.0 * released) +
                     " nN nm, full spatula) and instabilities are set to stop";
    return failure;
  }
  point.after_jump = true;   // the smallest step still crosses the snap: it is the jump
  point.released = released;
  point.dissipated += released;
  if (log_)
    *log_ << "  snap within the smallest step to " << stepping.name << " = " << load_text(load / stepping.unit)
          << ": counted as a jump, released " << load_text(2.0 * released) << " nN nm (full spatula)\n";
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
  point.step_control.increment = stepping.increment;
  stepping.failed.save(point.step_control);
  take_step(trial, point, taken, table, on_point);
}

const char* LoadPath::load_name(Master controlled)
{
  // The rotation master is the end face's rotation from the initial inclination (theta_y - theta_s).
  return controlled == Master::rotation ? "rotation theta_y - theta_s" : controlled == Master::lift ? "lift" : "slide";
}

PredictorWeights predictor_weights(StepParameters::Predictor predictor, double increment, double previous_increment,
                                   double older_increment)
{
  const double t = increment, h2 = previous_increment, h1 = older_increment;
  PredictorWeights w;
  if (predictor == StepParameters::Predictor::quadratic && h2 > 0.0 && h1 > 0.0) {
    // The Lagrange polynomial through (-h1 - h2, older), (-h2, previous), (0, current) at t, in Newton's form:
    // current + (t + c) (current - previous) / h2 - c (previous - older) / h1,  c = t (t + h2) / (h1 + h2).
    const double c = t * (t + h2) / (h1 + h2);
    w = {1.0 + (t + c) / h2, -(t + c) / h2 - c / h1, c / h1};
  } else if (h2 > 0.0) {   // secant: current + t (current - previous) / h2
    w = {1.0 + t / h2, -t / h2, 0.0};
  }
  return w;
}

void LoadPath::predict(Vector& trial, Master controlled, double load, double increment,
                       StepParameters::Predictor predictor) const
{
  const auto w = predictor_weights(predictor, increment, previous_increment_, older_increment_);
  trial.update(w.previous, *previous_, w.older, *older_, 0.0);
  trial.update(w.current, *x_, 1.0);
  model_.system().set_master(trial, controlled, load);
}

double LoadPath::released_energy(const LoadPoint& point) const
{
  // The work of the reactions (trapezoidal rule) minus the change of Pi_int + Pi_c since the last point.
  const auto& last = points_.back();
  return (point.external_work - last.external_work) -
         (point.internal_energy + point.contact_energy - last.internal_energy - last.contact_energy);
}

std::variant<double, Failure> LoadPath::pass_fold(Master controlled, double unreached,
                                                  const discretization::MasterControl& control, double direction,
                                                  double smallest_increment, double unit,
                                                  const std::string& newton_failure, const Callback& on_point)
{
  auto& system = model_.system();
  const char* name = load_name(controlled);
  if (past_folds_ == PastFolds::jump) {   // an instability: jump at the unreached load to the far side
    if (log_) *log_ << "  " << name << " = " << load_text(unreached / unit) << ": no equilibrium near the last one "
                    << "(an instability); jumping to the next stable state" << std::endl;
    auto failure = jump(controlled, unreached, on_point);
    system.set_control(control);
    if (failure) {
      failure->load = unreached / unit;   // in the load's unit, as every other failure
      return *failure;
    }
    return unreached;
  }
  if (past_folds_ == PastFolds::arc_length && direction > 0) {   // go round the fold, resume beyond
    if (log_) *log_ << "  " << name << " = " << load_text(unreached / unit) << " not reachable on this branch: "
                    << "arc-length continuation round the fold\n";
    auto failure = arc_length(controlled, unreached, control, *arc_length_, unit,
                              [&](const LoadPoint& p, const Vector& x) {
                                if (detachment_test_ && detachment_test_(p)) detached_ = true;
                                if (on_point) on_point(p, x);
                              });
    system.set_control(control);
    if (failure && !detached_) return *failure;
    return system.master(*x_, controlled);
  }
  Failure failure;
  failure.step = next_step();
  failure.load = unreached / unit;
  failure.smallest_increment = smallest_increment / unit;
  failure.reason = newton_failure;
  return failure;
}

void LoadPath::take_step(const Vector& state, const LoadPoint& point, double increment, const std::string& table,
                         const Callback& on_point)
{
  older_->assign(*previous_);
  older_increment_ = previous_increment_;
  previous_->assign(*x_);
  x_->assign(state);
  previous_increment_ = increment;
  points_.push_back(point);
  if (log_ && tables_) *log_ << table;
  if (detachment_test_ && detachment_test_(points_.back())) detached_ = true;
  if (on_point) on_point(points_.back(), *x_);
}

std::optional<LoadPoint> LoadPath::descend_early(Master controlled, double load, Vector& state)
{
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: early energy descent"));
  ++early_descents_.tried;
  state.assign(*x_);
  model_.system().set_master(state, controlled, load);
  const auto outcome = descend(state);
  if (const auto* reason = std::get_if<std::string>(&outcome)) {
    if (log_) *log_ << "  the descent found no stable state (" << *reason << ")\n";
    return std::nullopt;
  }
  auto point = measure(state, std::get<int>(outcome), -1);
  const double released = released_energy(point);
  if (std::abs(released) > jump_.step_balance_tolerance) {
    if (log_) *log_ << "  the descent released " << load_text(2.0 * released) << " nN nm (full spatula), more than "
                    << "the step balance tolerance: a snap proper\n";
    return std::nullopt;
  }
  ++early_descents_.taken;
  if (log_) *log_ << "  the descent reached a state on this branch in " << std::get<int>(outcome)
                  << " iterations (released " << load_text(2.0 * released) << " nN nm, full spatula): an ordinary step\n";
  return point;
}

void LoadPath::accept(const Vector& x, int iterations, int negative_pivots, const Callback& on_point)
{
  previous_->assign(*x_);
  x_->assign(x);
  previous_increment_ = older_increment_ = 0.0;
  points_.push_back(measure(*x_, iterations, negative_pivots));
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

double LoadPath::elapsed_seconds() const { return now() - started_; }

void LoadPath::restart(const Vector& x, const LoadPoint& point, bool resume_step_control)
{
  x_->assign(x);
  previous_->assign(x);
  previous_increment_ = older_increment_ = 0.0;
  points_.clear();
  jump_in_progress_.reset();   // (resume_jump() after this sets the one to go on with)
  resumed_jump_.reset();
  step_offset_ = point.step;
  if (resume_step_control) resumed_control_ = point.step_control;
  else resumed_control_.reset();
  if (point.seconds > 0.0) started_ = now() - point.seconds;   // a resumed run's clock goes on
  auto measured = measure(*x_, point.newton_iterations, point.negative_pivots);
  measured.step = point.step;
  measured.external_work = point.external_work;
  measured.dissipated = point.dissipated;
  points_.push_back(measured);
}

const std::vector<std::string>& JumpParameters::refactor_names()
{
  static const std::vector<std::string> names = {"count", "cost"};
  return names;
}

void DescentCost::factored(double seconds, double decrease)
{
  seconds_ = seconds;
  decrease_ = decrease;
}

bool DescentCost::keep(double seconds, double decrease)
{
  const bool keep = decrease > 0.0 && decrease * seconds_ >= decrease_ * seconds;   // rate >= the cycle's rate
  seconds_ += seconds;
  decrease_ += decrease;
  return keep;
}

// Minimizes Pi at the current load from x (shifted Newton + expanding line search on Pi), then confirms with plain
// Newton. Returns the iterations used, or the reason it failed.
// The state of one energy descent: the shift eta of the tangent (relative to `scale`, the mean diagonal), where its
// iterations went (for the diagnosis of a descent that does not settle) and their table.
struct LoadPath::Descent {
  double eta = 0.0, scale = 0.0;
  int iteration = 0;
  int indefinite = 0, no_decrease = 0, accepted = 0;
  bool unshifted_tried = false;   // at the current state, with a small gradient
  int kept = 0;                   // further iterations the current (positive definite) factors may serve
  DescentCost cost;               // refactor = cost: the current factors' cycle
  double cycle_began = 0.0;       // when fresh factors were last asked for (set as each descent call begins)
  double residual = 0.0;          // |f| at the last iteration [nN]
  double began = now(), reported = now();   // a progress line at least every minute of a long descent
  std::ostringstream table;

  // The kept factors are given up: a new cycle begins.
  void refactor()
  {
    kept = 0;
    cycle_began = now();
  }
  // A stiffer shift (the tangent was indefinite, or Pi did not decrease along its direction).
  void shift_more(double growth) { eta = eta == 0.0 ? 1e-6 * scale : growth * eta; }

  void row(bool tables, int negative, double residual_norm, double step, double energy)
  {
    if (!tables) return;
    table << "  descent  " << std::setw(9) << iteration << "  " << std::setw(9) << eta / scale << "  " << std::setw(7)
          << negative << "  " << std::setw(9) << residual_norm << "  " << std::setw(9) << step << "  "
          << std::setprecision(8) << energy << std::setprecision(2) << "\n";
  }
};

solvers::MumpsSolver& LoadPath::descent_solver()
{
  if (!descent_solver_) {   // the user's MUMPS options, but exact LDL^T factors: the descent needs their inertia
    auto parameters = newton_.linear_solver().parameters().mumps;
    parameters.symmetric = true;
    parameters.low_rank_tolerance = 0.0;
    descent_solver_ = std::make_unique<solvers::MumpsSolver>(model_.system().owned_map(), parameters);
  }
  return *descent_solver_;
}

double LoadPath::descent_line_search(const Vector& x, const Vector& direction, double energy, double slope,
                                     Vector& trial, double& best_energy) const
{
  // Armijo's condition on Pi, with expansion: negative curvature means going further lowers Pi more.
  auto& system = model_.system();
  double step = 1.0, best_step = 0.0;
  best_energy = energy;
  for (int trial_count = 0; trial_count < 30; ++trial_count) {
    trial.update(1.0, x, step, direction, 0.0);
    const auto evaluation = system.evaluate(trial, nullptr, false);
    const double value_at = evaluation.energy();
    const bool sufficient = evaluation.admissible && value_at <= energy + 1e-4 * step * slope;
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
  return best_step;
}

LoadPath::DescentPoint LoadPath::descent_point(const Vector& x, Descent& d, bool fresh, Vector& f)
{
  auto& system = model_.system();
  if (fresh) system.set_damping(d.eta, Teuchos::rcpFromRef(x));   // anchored at x: a pure shift, f unchanged
  const auto evaluation = system.evaluate(x, &f, fresh);
  if (fresh) system.set_damping(0.0, Teuchos::null);
  DescentPoint point{evaluation.admissible, evaluation.energy(), f.norm2(), 0};
  if (!point.admissible) return point;
  if (d.scale == 0.0) d.scale = system.mean_diagonal();
  if (fresh) {
    try {
      descent_solver().factor(*system.jacobian());
      point.negative_pivots = descent_solver().statistics().negative_pivots;
    } catch (const std::exception&) {
      point.negative_pivots = 1;   // singular: treat like indefinite
    }
  }
  return point;
}

void LoadPath::after_descent_step(Descent& d, bool fresh, double step, double decrease, double iteration_began)
{
  if (jump_.refactor == JumpParameters::Refactor::cost && fresh) {   // a new cycle: one kept iteration at least
    d.cost.factored(now() - d.cycle_began, decrease);
    d.kept = 1;
  } else if (jump_.refactor == JumpParameters::Refactor::cost) {
    // The clocks differ by rank: any rank that would refactor decides for all.
    int keep = d.cost.keep(now() - iteration_began, decrease) ? 1 : 0;
    Teuchos::reduceAll(*model_.system().owned_map()->getComm(), Teuchos::REDUCE_MIN, keep, Teuchos::outArg(keep));
    if (keep) d.kept = 1;
    else d.refactor();
  } else if (fresh) {
    d.kept = jump_.reused_factors;
  } else {
    --d.kept;
  }
  if (fresh) {
    d.eta = step >= 1.0 ? 0.25 * d.eta : 2.0 * d.eta;
    if (d.eta < 1e-9 * d.scale) d.eta = 0.0;
  }
  // refactor = count: a short step means the factors no longer fit the energy's curvature here
  if (jump_.refactor == JumpParameters::Refactor::count && step < 0.5) d.kept = 0;
}

std::optional<std::string> LoadPath::descend_to_small_gradient(Vector& x, Descent& d, double small_gradient)
{
  auto& system = model_.system();
  auto f = system.create_vector(), direction = system.create_vector(), trial = system.create_vector();
  d.cycle_began = now();   // a cycle is not charged with the confirming Newton between two calls
  // After every iteration, accepted or not (an indefinite try costs a factorization: a minute on the paper's mesh),
  // a jump's descent is offered to the watch (checkpoint, signal).
  for (; d.iteration < jump_.maximum_iterations; watch_descent(d, x), ++d.iteration) {
    const double iteration_began = now();
    // Kept factors (of a positive definite shifted tangent at an earlier state) still give a descent direction
    // -M^-1 f; the iteration then needs only f and Pi. Otherwise the tangent at x is assembled and factored.
    const bool fresh = d.kept == 0;
    const auto point = descent_point(x, d, fresh, *f);
    if (!point.admissible) return std::string("an element inverted during the energy descent");
    if (point.negative_pivots > 0) {   // not a descent direction yet: shift more
      d.row(tables_, point.negative_pivots, point.residual, 0.0, point.energy);
      ++d.indefinite;
      d.shift_more(jump_.shift_growth);
      continue;
    }
    // Near a stable minimum (positive definite tangent, small gradient): plain Newton finishes. The energy alone
    // cannot resolve the last digits (its changes fall below its rounding), the gradient can. A small gradient found
    // with a shift is tested once without it: is the unshifted tangent positive definite there? (Without this a
    // descent that has reached the minimum keeps raising the shift, since no step can lower Pi any more.)
    d.residual = point.residual;
    if (log_ && now() - d.reported >= 60.0) {   // (only rank 0 has a log: no collective depends on this clock)
      d.reported = now();
      std::ostringstream line;   // formatted apart: the log's own format stays as it is
      line << "  descent: iteration " << d.iteration << ", |f| = " << std::scientific << std::setprecision(2)
           << point.residual << " nN, Pi = " << std::fixed << std::setprecision(4) << point.energy << " nN nm, "
           << std::setprecision(1) << (d.reported - d.began) / 60.0 << " min";
      *log_ << line.str() << std::endl;
    }
    if (point.residual < small_gradient && (d.eta == 0.0 || !d.unshifted_tried || !fresh)) {
      d.row(tables_, fresh ? point.negative_pivots : -1, point.residual, 0.0, point.energy);
      if (!fresh) {   // the tests below need the inertia at this state
        d.refactor();
        continue;
      }
      if (d.eta == 0.0) return std::nullopt;
      d.unshifted_tried = true;
      d.eta = 0.0;
      continue;
    }
    descent_solver().apply(*f, *direction);
    if (!fresh) descent_solver().count_reuse();   // an iteration served by kept factors
    direction->scale(-1.0);
    double best_energy = point.energy;
    const double slope = f->dot(*direction);
    const double best_step = descent_line_search(x, *direction, point.energy, slope, *trial, best_energy);
    d.row(tables_, fresh ? point.negative_pivots : -1, point.residual, best_step, best_energy);
    if (best_step == 0.0 && !fresh) {   // the kept factors are out of date: fresh ones at this state
      d.cost.keep(now() - iteration_began, 0.0);   // (their cycle's last, fruitless iteration)
      d.refactor();
      continue;
    }
    // A descent direction along which Pi does not measurably decrease: rounding; let Newton finish. But a direction
    // that is not one (slope >= 0: the factors of a nearly singular tangent whose inertia showed no negative pivot
    // lost it to rounding) is shifted like an indefinite tangent.
    if (best_step == 0.0 && d.eta == 0.0 && slope < 0.0) return std::nullopt;
    if (best_step == 0.0 && slope >= 0.0 && tables_)
      d.table << "  descent  (not a descent direction: slope " << slope << " nN nm; shifting the tangent)\n";
    if (best_step == 0.0) {   // no decrease along this direction: stiffen the shift
      ++d.no_decrease;
      d.shift_more(jump_.shift_growth);
      continue;
    }
    ++d.accepted;
    d.unshifted_tried = false;
    x.update(best_step, *direction, 1.0);
    after_descent_step(d, fresh, best_step, point.energy - best_energy, iteration_began);
  }
  return std::nullopt;
}

void LoadPath::watch_descent(const Descent& d, const Vector& x)
{
  if (!jump_in_progress_) return;   // only a jump's descent is checkpointed
  jump_in_progress_->state->assign(x);
  jump_in_progress_->shift = d.eta;
  jump_in_progress_->scale = d.scale;
  jump_in_progress_->iterations = d.iteration + 1;
  if (descent_watch_) descent_watch_();
}

std::variant<int, std::string> LoadPath::descend(Vector& x, const JumpInProgress* resumed)
{
  Descent d;
  if (resumed) {
    d.eta = resumed->shift;
    d.scale = resumed->scale;
    d.iteration = resumed->iterations;
  }
  auto start = model_.system().create_vector();
  start->assign(x);
  d.table << std::scientific << std::setprecision(2);
  if (tables_) d.table << "  descent  iteration  eta/scale  neg.piv   |f| [nN]       step  Pi [nN nm]\n";
  // After Newton failed to confirm a state with a small gradient (just past a fold the gradient is small but no
  // equilibrium is near), the descent goes on and asks Newton again only at a gradient a thousand times smaller
  // (the minimum it then reaches can be very flat: a snapped-off face far out in the Lennard-Jones tail), up to
  // three times in all.
  double small_gradient = 1e-3;   // |f| [nN]
  auto confirmed = model_.system().create_vector();
  for (int confirmations = 1;; ++confirmations) {
    if (auto error = descend_to_small_gradient(x, d, small_gradient)) {
      jump_in_progress_.reset();   // no state worth going on from
      return *error;
    }
    if (log_ && tables_) *log_ << d.table.str();
    d.table.str("");
    if (d.iteration >= jump_.maximum_iterations) {   // jump_in_progress_ is kept: more iterations can go on from it
      start->update(1.0, x, -1.0);
      std::ostringstream reason;
      reason << "no stable state within " << jump_.maximum_iterations << " iterations (" << d.accepted
             << " descent steps moved the state by at most " << std::setprecision(3) << start->normInf() << " nm; "
             << d.indefinite << " shifts for an indefinite tangent, " << d.no_decrease << " for no decrease of Pi; "
             << "final shift " << d.eta / d.scale << " x the mean diagonal)";
      return reason.str();
    }
    confirmed->assign(x);
    const auto plain = newton_.solve(*confirmed, nullptr, true);   // the give-up rules: a hopeless try ends soon
    if (plain.converged) {
      x.assign(*confirmed);
      return d.iteration + (plain.iterations.empty() ? 0 : plain.iterations.back().iteration);
    }
    if (confirmations == 3) {
      jump_in_progress_.reset();
      return "Newton did not confirm the state the energy descent reached (" + plain.failure + ")";
    }
    small_gradient = 1e-3 * std::min(small_gradient, d.residual);
    if (tables_) d.table << "  descent  (Newton did not confirm: " << plain.failure << "; descending further)\n";
  }
}

std::optional<Failure> LoadPath::jump(Master controlled, double value, const Callback& on_point)
{
  return jump(controlled, value, on_point, nullptr);
}

std::optional<Failure> LoadPath::jump(Master controlled, double value, const Callback& on_point,
                                      const JumpInProgress* resumed)
{
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: jump past instability"));
  auto& system = model_.system();
  const auto before = points_.back();
  auto x = system.create_vector();
  if (resumed) {
    x->assign(*resumed->state);
  } else {
    x->assign(*x_);
    system.set_master(*x, controlled, value);
  }
  jump_in_progress_ = resumed ? *resumed : JumpInProgress{controlled, value, Teuchos::null, 0.0, 0.0, 0};
  jump_in_progress_->state = system.create_vector();   // its own copy, updated as the descent goes
  jump_in_progress_->state->assign(*x);
  const auto outcome = descend(*x, resumed);
  if (std::holds_alternative<int>(outcome)) jump_in_progress_.reset();   // done: the path goes on from its state
  if (const auto* reason = std::get_if<std::string>(&outcome)) {
    // How far the descent got: the share of the adhesion energy its last state still holds.
    const auto last = system.evaluate(*x, nullptr, false);
    const double kept = before.contact_energy != 0.0 ? last.contact_energy / before.contact_energy : 1.0;
    Failure failure;
    failure.step = next_step();
    failure.load = value;
    failure.reason = "jump past the instability failed: " + *reason + "; the descent's last state kept " +
                     std::to_string(static_cast<int>(std::lround(100.0 * kept))) + " % of the adhesion energy";
    return failure;
  }
  const int iterations = std::get<int>(outcome);
  accept(*x, iterations, -1, {});
  auto& after = points_.back();
  const double released = (before.internal_energy + before.contact_energy) -
                          (after.internal_energy + after.contact_energy) + (after.external_work - before.external_work);
  if (jump_.step_balance_tolerance > 0.0 && std::abs(released) <= jump_.step_balance_tolerance) {
    // Newton had stalled, but the descent stayed on the branch: by the measure of the step balance check, an
    // ordinary step, not a snap.
    if (log_)
      *log_ << "  the descent stayed on the branch in " << iterations << " iterations (released "
            << load_text(2.0 * released) << " nN nm, full spatula, within the step balance tolerance): an ordinary step\n";
  } else {
    after.after_jump = true;
    after.released = released;
    after.dissipated += released;
    if (log_)
      *log_ << "  jumped in " << iterations << " iterations (energy descent, then Newton), released "
            << load_text(2.0 * released) << " nN nm (full spatula)\n";
  }
  if (detachment_test_ && detachment_test_(after)) detached_ = true;
  if (on_point) on_point(after, *x_);
  return std::nullopt;
}

}  // namespace spatula::analysis
