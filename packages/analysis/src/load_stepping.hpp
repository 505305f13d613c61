#pragma once
// Quasi-static load stepping along one end-face master (the rotation alpha or the lift w): adaptive increments
// with cut-back on failure, a predictor from the last converged states, and the work of the reactions along the path.
//
// Each converged step is a LoadPoint; the run stops at the target, or with a Failure naming the step, the load,
// the smallest increment tried and the Newton diagnosis (never a silently accepted state).
#include "analysis/load_history.hpp"
#include "analysis/load_path_log.hpp"
#include "analysis/step_control.hpp"
#include "solvers/energy_minimizer.hpp"
#include "solvers/newton.hpp"

#include <functional>
#include <memory>
#include <iosfwd>
#include <optional>
#include <variant>
#include <string>
#include <vector>

namespace spatula::analysis {

class InstabilityPolicy;
using discretization::Master;
using discretization::Vector;

// The jump past an instability at fixed load: the energy minimizer (solvers/energy_minimizer.hpp) from the last
// stable state, with the load held, to a stable state on the far side of the snap, like a quasi-static snap with
// viscous dissipation: the energy released in the jump is reported.
//
// A snap can also hide inside a load step: Newton converges, but on another branch, and the work of the reactions
// (trapezoidal rule) no longer matches the change of Pi_int + Pi_c over the step. A converged step whose imbalance
// |Delta W - Delta Pi| exceeds step_balance_tolerance is therefore cut back like a failed one; at the smallest
// increment it is accepted as a jump, the imbalance being the energy it released. The same measure classifies a
// descent's outcome: one that releases no more than the tolerance stayed on the branch (Newton had stalled where
// there was no limit point) and is recorded as an ordinary step, not as a jump.
struct JumpParameters : solvers::MinimizerParameters {
  // After this many failed attempts in a row from one converged state, the energy descent is tried at the load of
  // the last one: taken as an ordinary step if it releases no more than the step balance tolerance (a micro-snap of
  // the peel front, which bisecting down to the smallest increment would reach only after many more failed
  // attempts); otherwise the increments bisect towards it as before, and no early descent is tried again until the
  // path has passed that load (a resumed run forgets a refusal). Only with jumps past folds and a step balance
  // tolerance, and not where the cut would leave the smallest increment (the jump descends there anyway).
  // 0: never (bisect to the smallest increment, then jump).
  int descend_after_failures = 0;
  double step_balance_tolerance = 0.0;   // [nN nm, half model]; 0: not checked
};

// Arc-length continuation (LOCA) in the controlled master, used to go round folds of the load path.
struct ArcLengthParameters {
  double initial = 0.02, minimum = 1e-5, maximum = 0.5;   // arc-length steps (LOCA's scaled norm)
  int maximum_steps = 200;
};

struct Failure {
  int step = 0;
  double load = 0.0;          // the load value that could not be reached (deg or nm)
  double smallest_increment = 0.0;
  std::string reason;
  // A force-controlled path (advance_force) found no equilibrium at a larger force: the largest force the face
  // carries on this branch (under a dead load the limit point is not passed: beyond it no state holds the load).
  bool largest_force = false;
  // A jump that found no stable state, whose descent's last state has no contact point within the gap of the
  // strongest attraction: the pad had let go of the substrate on the way.
  bool let_go = false;
};

class LoadPath {
public:
  LoadPath(solvers::SpatulaModel& model, const solvers::EquilibriumSolver& equilibrium, std::ostream* log,
           bool convergence_tables);

  // The current state (starts undeformed, rotation and lift zero).
  Vector& state() { return *x_; }
  const LoadPoint& last() const { return history_.last(); }
  const std::vector<LoadPoint>& points() const { return history_.points(); }
  double elapsed_seconds() const { return history_.elapsed_seconds(); }   // a resumed run's included

  // Moves `controlled` from its current value to `target`; `control` says which masters are prescribed (the
  // controlled one always is; the others keep their values). Calls `on_point` after every converged step.
  // Where the increment has to be cut below its minimum (a fold of the path: the load cannot grow along this
  // branch), the path is followed by arc-length continuation round the fold if enabled, and stepping resumes on
  // the far side. Stops early, without failure, once `detached()` is true. Returns the failure, if any.
  using Callback = std::function<void(const LoadPoint&, const Vector&)>;
  std::optional<Failure> advance(Master controlled, double target, discretization::MasterControl control,
                                 const StepParameters& steps, double unit, const Callback& on_point);
  // The same with the dead load on the free master `loaded` as the load (MasterControl::applied; moment or force,
  // half model): from the reaction the face carries at the current state to `target`, every step an equilibrium
  // under that load. Where no equilibrium follows at a larger load (a limit point: the face cannot carry more) the
  // path stops with a Failure marked largest_force; instabilities are not passed under a dead load. The load stays
  // applied after the call (a later advance's control replaces it).
  std::optional<Failure> advance_force(Master loaded, double target, discretization::MasterControl control,
                                       const StepParameters& steps, double unit, const Callback& on_point);

  // Follows the path by arc-length in `controlled` from the current state (it may fall and rise again round a
  // fold) until it exceeds `resume_above` (in the direction of increasing load) or the step budget is spent.
  // Every converged point is recorded and reported like a load step.
  std::optional<Failure> arc_length(Master controlled, double resume_above, discretization::MasterControl control,
                                    const ArcLengthParameters& parameters, double unit, const Callback& on_point);

  // How to get past a fold (an instability): the policy (instability_policy.hpp: stop, jump at fixed load, or
  // arc-length continuation); none: stop.
  void set_instability_policy(std::shared_ptr<const InstabilityPolicy> policy) { policy_ = std::move(policy); }
  void set_jump_parameters(const JumpParameters& parameters)
  {
    jump_ = parameters;
    minimizer_.set_parameters(parameters);
  }
  // Where a step met a fold: the controlled master, the load it could not reach (internal units), which masters are
  // prescribed, the sense of travel (+1, -1) and the load's unit.
  struct Fold {
    Master controlled;
    double unreached;
    discretization::MasterControl control;
    double direction, unit;
  };
  // The means a policy passes a fold by: a jump at the unreached load to the next stable state, or arc-length
  // continuation round the fold until the load passes the unreached one. Each returns the load reached beyond the
  // fold (stepping resumes there) or why the path stops.
  std::variant<double, Failure> jump_past(const Fold& fold, const Callback& on_point);
  std::variant<double, Failure> continue_past(const Fold& fold, const ArcLengthParameters& parameters,
                                              const Callback& on_point);
  // Jumps at fixed `controlled` = value from the current state to a stable equilibrium (see JumpParameters).
  std::optional<Failure> jump(Master controlled, double value, const Callback& on_point);

  // A jump whose energy descent is under way: where it jumps (the controlled master held at `value`, in internal
  // units), the descent's state, its tangent shift eta with the mean diagonal it is measured against, and its
  // iterations so far. A descent can take an hour on the paper's mesh; a checkpoint of it lets a stopped run go on
  // inside the jump.
  struct JumpInProgress {
    Master controlled = Master::rotation;
    double value = 0.0;
    Teuchos::RCP<Vector> state;
    double shift = 0.0, scale = 0.0;
    int iterations = 0;
  };
  // While a jump's descent runs, and after a jump that stopped at its iteration limit or was interrupted (a
  // signal thrown from the watch); null otherwise.
  const JumpInProgress* jump_in_progress() const { return jump_in_progress_ ? &*jump_in_progress_ : nullptr; }
  // Called on every rank after every descent iteration of a jump (collective callers welcome: every rank runs the
  // same iterations). It may throw to stop the run; jump_in_progress() then still holds the jump.
  void set_descent_watch(std::function<void()> watch) { descent_watch_ = std::move(watch); }
  // Goes on with a checkpointed jump: the next advance first finishes it from its descent's state, shift and
  // iteration count (call after restart(), from the state the jump started from), if that advance is in the jump's
  // master, reaches its value and jumps past folds; otherwise the jump is dropped (logged) and the path starts afresh.
  void resume_jump(JumpInProgress jump) { resumed_jump_ = std::move(jump); }
  // The detachment test that ends a path cleanly.
  void set_detachment_test(std::function<bool(const LoadPoint&)> test) { detachment_test_ = std::move(test); }
  // How the log reports an energy released: the model's value times `factor`, named `of_what` (a symmetric half
  // model reports the whole body's: 2, "full spatula"). Default: the model's own, "the model".
  void set_energy_report(double factor, std::string of_what)
  {
    report_factor_ = factor;
    report_of_ = std::move(of_what);
  }
  bool detached() const { return detached_; }
  // A test that ends an advance early at a converged point, without failure (a stage's stop rule: a force reached);
  // each advance starts with it unmet. null: none.
  void set_end_test(std::function<bool(const LoadPoint&)> test) { end_test_ = std::move(test); }
  bool ended() const { return ended_; }
  // Early descents (JumpParameters::descend_after_failures) tried, and taken as ordinary steps.
  struct EarlyDescents {
    int tried = 0, taken = 0;
  };
  const EarlyDescents& early_descents() const { return early_descents_; }
  // The factorizations of the jumps' energy descents (null before the first descent).
  const solvers::MumpsStatistics* descent_statistics() const { return minimizer_.statistics(); }

  // Replaces the current state by `guess` and solves for equilibrium at the current load (e.g. the pad pressed onto
  // a rough substrate before loading); the result becomes the path's first point (history reset).
  std::optional<Failure> equilibrate(const Vector& guess, discretization::MasterControl control);

  // Starts the path from a converged state read from a checkpoint; `point` carries its history (step number,
  // external work so far; when positive the wall time and when given the step controller's state: a resumed run goes
  // on as it would have); reactions and energies are recomputed. Later points are numbered on from its step.
  void restart(const Vector& x, const LoadPoint& point, bool resume_step_control = false);

  // Accepts a converged state found outside `advance` (continuation, restart): it becomes the new last point.
  void accept(const Vector& x, int iterations, int negative_pivots, const Callback& on_point);

private:
  LoadPoint measure(const Vector& x, int iterations, int negative_pivots) const
  {
    return history_.measure(model_.system(), x, iterations, negative_pivots);
  }
  // The steps of `advance`: the predictor, the energy a converged step released, passing a fold (the controlled
  // load's value beyond it, or why the path stops there), and taking a converged step.
  static const char* load_name(Master controlled, bool force = false);
  void predict(Vector& trial, double increment, StepParameters::Predictor predictor) const;
  std::variant<double, Failure> pass_fold(Master controlled, double unreached,
                                          const discretization::MasterControl& control, double direction,
                                          double smallest_increment, double unit, const std::string& newton_failure,
                                          const Callback& on_point);
  void take_step(const Vector& state, const LoadPoint& point, double increment, const std::string& table,
                 const Callback& on_point);
  // The point of the converged state x_ once a contact law with state has committed its history there (nothing to
  // do without one): Pi_c measured again from the committed history is the stored energy (the trial's held the
  // step's sliding too, which then counts in LoadPoint::sliding).
  LoadPoint committed(const LoadPoint& point);
  // One advance's state (load reached, next increment, failed loads), and its three outcomes of an attempt: a failed
  // one (an early descent, a cut increment, or below the smallest the way past the fold; a failure ends the path), a
  // converged one that crossed a snap (true: cut back and try again; at the smallest increment it is the jump), and a
  // converged step taken (the increment grows after an easy one).
  struct Stepping;
  // The steps of an advance from `value` of the load (the master's value, or with `force` its dead load) to `target`.
  std::optional<Failure> follow(Master controlled, bool force, double value, double target,
                                const discretization::MasterControl& control, const StepParameters& steps, double unit,
                                const Callback& on_point);
  void set_load(Stepping& stepping, Vector& trial, double load) const;   // the master's value or its dead load
  // Sets which masters are prescribed (and the dead loads); where that changes, the kept factors are renewed.
  void set_control(const discretization::MasterControl& control) const;
  std::optional<Failure> after_failed_attempt(Stepping& stepping, double load, Vector& trial,
                                              const std::string& newton_failure, const std::string& table,
                                              const Callback& on_point);
  std::variant<bool, Failure> crossed_snap(Stepping& stepping, double load, LoadPoint& point, const std::string& table);
  void take_converged_step(Stepping& stepping, const Vector& trial, LoadPoint& point, int iterations,
                           const std::string& table, const Callback& on_point);
  // The early descent of JumpParameters::descend_after_failures: the state it reached at `load` and its measure, if
  // it released no more than the step balance tolerance.
  std::optional<LoadPoint> descend_early(Master controlled, double load, Vector& state);
  solvers::SpatulaModel& model_;
  const solvers::EquilibriumSolver& equilibrium_;   // the corrector of every step
  std::ostream* log_;
  bool tables_;
  Teuchos::RCP<Vector> x_, previous_, older_;   // the last three converged states of this advance
  double previous_increment_ = 0.0;   // x_ - previous_ in the load (0: no predictor)
  double older_increment_ = 0.0;      // previous_ - older_ in the load (0: no quadratic predictor)
  LoadHistory history_;
  std::optional<StepControllerState> resumed_control_;   // carried by a restart (LoadPoint::step_control)
  CurveResolution curve_;   // of the stage being followed
  int next_step() const { return history_.next_step(); }
  std::shared_ptr<const InstabilityPolicy> policy_;
  bool jumps() const;   // the policy jumps at fixed load (early descents, a checkpointed jump)
  JumpParameters jump_;
  solvers::EnergyMinimizer minimizer_;   // of the jumps, early descents and equilibrate()
  std::function<bool(const LoadPoint&)> detachment_test_, end_test_;
  bool detached_ = false, ended_ = false;
  void check_end(const LoadPoint& point);   // the detachment and end tests at a converged point
  std::optional<JumpInProgress> jump_in_progress_, resumed_jump_;
  std::function<void()> descent_watch_;
  // The jump's descent from a checkpoint of it, if resumed_jump_ is in this master (the first thing an advance does).
  std::optional<Failure> finish_resumed_jump(Master controlled, double unit, const Callback& on_point);
  std::optional<Failure> jump(Master controlled, double value, const Callback& on_point,
                              const JumpInProgress* resumed);
  EarlyDescents early_descents_;
  double report_factor_ = 1.0;
  std::string report_of_ = "the model";
  std::string released_text(double released) const { return load_text(report_factor_ * released) + " nN nm"; }
};

}  // namespace spatula::analysis
