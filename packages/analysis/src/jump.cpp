// The jump past an instability: the energy descent at fixed load (shifted Newton with an expanding line search on
// Pi, its own MUMPS solver and cost rule), its checkpointable progress, and the jump's classification.
#include "analysis/load_stepping.hpp"
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
  // A shift this far above the tangent's mean diagonal leaves a steepest descent with steps of rounding size: no
  // tangent of a body that is still connected is that indefinite, so the descent stops instead of growing it further.
  static constexpr double largest_shift = 1e10;
  bool shift_exhausted() const { return eta > largest_shift * scale; }
  std::string exhausted_reason() const
  {
    std::ostringstream reason;
    reason << "the energy descent's shift passed " << largest_shift << " x the tangent's mean diagonal at iteration "
           << iteration << " (" << indefinite << " shifts for an indefinite tangent, " << no_decrease
           << " for no decrease of Pi): no descent direction exists at this state";
    return reason.str();
  }

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
    auto parameters = equilibrium_.linear_solver().parameters().mumps;
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
    } catch (const solvers::UnusableMatrix&) {
      point.negative_pivots = 1;   // singular: treat like indefinite (any other failure is not the matrix's: it ends the run)
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
      if (d.shift_exhausted()) return d.exhausted_reason();
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
      if (d.shift_exhausted()) return d.exhausted_reason();
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
    const auto plain = equilibrium_.solve(*confirmed, nullptr, true);   // the give-up rules: a hopeless try ends soon
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
