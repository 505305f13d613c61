// The jump past an instability: the energy minimizer at fixed load, its checkpointable progress, and the jump's
// classification (a snap, or a descent that stayed on the branch).
#include "analysis/load_stepping.hpp"
#include "analysis/load_path_log.hpp"

#include "parameters/parameter_validation.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <variant>

namespace spatula::analysis {

std::variant<double, Failure> LoadPath::jump_past(const Fold& fold, const Callback& on_point)
{
  if (log_)
    *log_ << "  " << load_name(fold.controlled) << " = " << load_text(fold.unreached / fold.unit)
          << ": no equilibrium near the last one (an instability); jumping to the next stable state" << std::endl;
  auto failure = jump(fold.controlled, fold.unreached, on_point);
  set_control(fold.control);
  if (failure) {
    failure->load = fold.unreached / fold.unit;   // in the load's unit, as every other failure
    return *failure;
  }
  return fold.unreached;
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

std::optional<LoadPoint> LoadPath::descend_early(Master controlled, double load, Vector& state)
{
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: early energy descent"));
  ++early_descents_.tried;
  state.assign(*x_);
  model_.system().set_master(state, controlled, load);
  const auto outcome = minimizer_.minimize(state);
  if (!outcome.found || outcome.on_descent_law) {   // an ordinary step ends on an equilibrium of the law's own
    if (log_)
      *log_ << "  the descent found no stable state ("
            << (outcome.found ? "only one of the descent law's" : outcome.failure) << ")\n";
    return std::nullopt;
  }
  auto point = measure(state, outcome.iterations, -1);
  const double released = history_.released_energy(point);
  if (std::abs(released) > jump_.step_balance_tolerance) {
    if (log_) *log_ << "  the descent released " << released_text(released) << " (" << report_of_ << "), more than "
                    << "the step balance tolerance: a snap proper\n";
    return std::nullopt;
  }
  ++early_descents_.taken;
  if (log_) *log_ << "  the descent reached a state on this branch in " << outcome.iterations
                  << " iterations (released " << released_text(released) << ", " << report_of_ << "): an ordinary step\n";
  return point;
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
  const auto before = last();
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
  solvers::DescentProgress progress;
  if (resumed) progress = {resumed->shift, resumed->scale, resumed->iterations};
  const auto outcome = minimizer_.minimize(*x, resumed ? &progress : nullptr,
                                           [this](const Vector& state, const solvers::DescentProgress& now) {
                                             jump_in_progress_->state->assign(state);
                                             jump_in_progress_->shift = now.shift;
                                             jump_in_progress_->scale = now.scale;
                                             jump_in_progress_->iterations = now.iterations;
                                             if (descent_watch_) descent_watch_();
                                           });
  // Done, the path goes on from its state; or no state worth going on from. A descent stopped at its iteration
  // limit is kept: more iterations can go on from it.
  if (outcome.found || !outcome.can_go_on) jump_in_progress_.reset();
  if (!outcome.found) {
    // How far the descent got: the share of the adhesion energy its last state still holds, and how far the part
    // of the pad that still adheres has slid along the substrate since the jump began (a pad sliding off, not
    // lifting off, goes on sliding).
    const auto last = system.evaluate(*x, nullptr, false);
    const double kept = before.contact_energy != 0.0 ? last.contact_energy / before.contact_energy : 1.0;
    const auto slip = system.contact_gap_changes(*x_, *x, 1.0);
    const bool let_go = slip.adhering_area == 0.0;
    std::ostringstream reason;
    reason << "jump past the instability failed: " << outcome.failure << "; the descent's last state kept "
           << std::lround(100.0 * kept) << " % of the adhesion energy";
    if (!let_go)
      reason << ", its adhering part slid " << std::fixed << std::setprecision(1) << slip.mean_slip
             << " nm along the substrate (mean)";
    else
      reason << ", no contact point within the gap of the strongest attraction";
    Failure failure;
    failure.step = next_step();
    failure.load = value;
    failure.reason = reason.str();
    failure.let_go = let_go;
    return failure;
  }
  const int iterations = outcome.iterations;
  {
    std::optional<discretization::DescentLawScope> descent_law;   // the descent law's equilibrium is committed under
    if (outcome.on_descent_law) descent_law.emplace(system);        // it (the next step starts there)
    accept(*x, iterations, -1, {});
  }
  if (outcome.on_descent_law && log_)
    *log_ << "  the jump's state is an equilibrium of the energy its descent minimized, committed under it\n";
  const auto& after = last();
  // (What sliding friction dissipated on the way is counted by LoadPoint::sliding, not again here.)
  const double released = (before.internal_energy + before.contact_energy) -
                          (after.internal_energy + after.contact_energy) + (after.external_work - before.external_work) -
                          (after.sliding - before.sliding);
  if (jump_.step_balance_tolerance > 0.0 && std::abs(released) <= jump_.step_balance_tolerance) {
    // Newton had stalled, but the descent stayed on the branch: by the measure of the step balance check, an
    // ordinary step, not a snap.
    if (log_)
      *log_ << "  the descent stayed on the branch in " << iterations << " iterations (released "
            << released_text(released) << ", " << report_of_ << ", within the step balance tolerance): an ordinary step\n";
  } else {
    history_.mark_last_as_jump(released);
    if (log_)
      *log_ << "  jumped in " << iterations << " iterations (energy descent, then Newton), released "
            << released_text(released) << " (" << report_of_ << ")\n";
  }
  check_end(after);
  if (on_point) on_point(after, *x_);
  return std::nullopt;
}

}  // namespace spatula::analysis
