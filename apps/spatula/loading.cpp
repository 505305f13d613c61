#include "loading.hpp"

#include "analysis/instability_policy.hpp"
#include "parameters/parameter_validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace spatula::app {

std::shared_ptr<const analysis::InstabilityPolicy> instability_policy(const LoadingParameters& loading)
{
  return analysis::InstabilityPolicies::instance().make(loading.past_instabilities, loading.arc_length_steps);
}

const std::vector<std::string>& loading_types()
{
  static const std::vector<std::string> types = {"none", "rotation", "lift", "stages"};
  return types;
}

namespace {

// The stages of 'Loading/type' = rotation (the rotation to theta_y) and lift (then the lift to 'final lift').
std::vector<Stage> fixed_stages(const LoadingParameters& p)
{
  if (p.type == LoadingType::none) return {};
  Stage rotation;
  rotation.name = "rotation";
  rotation.kind = StageKind::rotate;
  rotation.target = p.theta_y;
  rotation.steps = p.rotation_steps;
  rotation.free_lift = p.free_lift;
  rotation.checkpoints = true;
  if (p.type == LoadingType::rotation) return {rotation};
  Stage lift;
  lift.name = "lift";
  lift.kind = StageKind::lift;
  lift.target = p.final_lift;
  lift.relative = p.lift_relative;
  lift.steps = p.lift_steps;
  lift.free_slide = p.free_slide;
  return {rotation, lift};
}

}  // namespace

void LoadingParameters::declare(Teuchos::ParameterList& loading)
{
  const LoadingParameters d;   // the defaults
  using parameters::Range;
  parameters::declare_string(loading, "type", parameters::name_of(d.type, loading_types()),
                             "none: mesh only; rotation: rotate the end face to theta_y; lift: rotate to theta_y, "
                             "then raise the face to 'final lift'; stages: the stages of 'Stages' (then theta_y, final "
                             "lift, the 'during' keys and the Rotation and Lift Steps are not used)",
                             loading_types());
  parameters::declare_double(loading, "theta_y", d.theta_y,
                             "shaft inclination to reach (rotation) or hold (lift) [deg]",
                             Range::closed(-180.0, 180.0));
  parameters::declare_double(loading, "final lift", d.final_lift,
                             "the end face centre's lift at the end of a lift, along the lift direction (u_z at the "
                             "default 'pull angle') [nm]",
                             Range::closed(-1e4, 1e4));
  parameters::declare_bool(loading, "final lift relative", d.lift_relative,
                           "count 'final lift' from the u_z where the lift starts, not from the undeformed state");
  parameters::declare_bool(loading, "free lift during rotation", d.free_lift,
                           "zero net Z force on the end face while rotating (false: u_z held at 0)");
  parameters::declare_bool(loading, "free slide during lift", d.free_slide,
                           "zero net X force on the end face while lifting (false: u_x held); needs a law that holds "
                           "the pad tangentially (stiction): on a frictionless substrate the spatula could slide freely");
  parameters::declare_double(loading, "pull angle", d.pull_angle,
                             "beta, the angle of the lift direction to the substrate in the X-Z plane [deg]: the end "
                             "face is lifted along (cos beta, 0, sin beta) and slid along (sin beta, 0, -cos beta); "
                             "90: along Z and X. The curve reports Z and X components whatever beta",
                             Range::closed(0.0, 180.0));
  parameters::declare_bool(loading, "hold contact surface", d.hold_contact_surface,
                           "hold the pad's contact surface at Z = 0 (a structural check without adhesion)");
  analysis::StepParameters::declare(
      parameters::declare_sublist(loading, "Rotation Steps", "increments of theta_y [deg]"), d.rotation_steps);
  analysis::StepParameters::declare(parameters::declare_sublist(loading, "Lift Steps", "increments of u_z [nm]"),
                                    d.lift_steps);
  parameters::declare_string(loading, "past instabilities",
                             d.past_instabilities,
                             "where no equilibrium follows at a larger load (a snap): stop; jump at fixed load to the "
                             "next stable state by energy descent; or follow the path round the fold by arc-length "
                             "continuation (LOCA)",
                             analysis::InstabilityPolicies::instance().names());
  parameters::declare_string(loading, "restart file", d.restart_file,
                             "checkpoints.h5 of an earlier run to start from (empty: the undeformed spatula)");
  parameters::declare_double(loading, "restart theta_y", d.restart_theta_y, "the checkpoint to start from [deg]",
                             Range::closed(-180.0, 180.0));
  parameters::declare_string(loading, "restart from", d.restart_from_last_state ? "last state" : "checkpoint",
                             "which state of the restart file: the checkpoint at 'restart theta_y', or the last "
                             "converged state a stopped (interrupted or failed) run left (if it stopped inside a jump past "
                             "an instability, the restart goes on with that jump's energy descent)",
                             {"checkpoint", "last state"});
  parameters::declare_string(loading, "checkpoints at theta_y", "",
                             "comma-separated inclinations [deg] where a rotation writes checkpoints (e.g. 45,60)");
  auto& jump = parameters::declare_sublist(loading, "Jump", "energy descent past an instability");
  parameters::declare_int(jump, "maximum iterations", d.jump.maximum_iterations,
                          "iterations per jump (one restarted inside its descent counts those before the stop)",
                          Range::closed(1, 100000));
  parameters::declare_string(jump, "method",
                             parameters::name_of(d.jump.method, analysis::JumpParameters::method_names()),
                             "how a descent iteration moves: shifted newton (a Newton step on the tangent shifted "
                             "until positive definite, a line search on Pi) or trust region (truncated conjugate "
                             "gradients on the tangent within a trust region, preconditioned by kept factors, "
                             "following negative curvature; 'refactor' and 'reused factors' are then not used) or "
                             "auto (the trust region for systems of at least 'trust region from' unknowns, where a "
                             "factorization costs many solves; shifted newton below)",
                             analysis::JumpParameters::method_names());
  parameters::declare_int(jump, "trust region from", d.jump.trust_region_from,
                          "method = auto: unknowns from which a descent takes the trust region",
                          Range::closed(0, std::numeric_limits<int>::max()));
  parameters::declare_string(jump, "refactor",
                             parameters::name_of(d.jump.refactor, analysis::JumpParameters::refactor_names()),
                             "when a descent replaces its factors: count (after 'reused factors' further iterations) "
                             "or cost (fresh factors serve one more iteration, then more while the last one lowered "
                             "the energy at least as fast per second as their cycle has on average, factorization "
                             "included; 'reused factors' is then not used)", analysis::JumpParameters::refactor_names());
  parameters::declare_int(jump, "reused factors", d.jump.reused_factors,
                          "refactor = count: descent iterations one positive definite factorization may serve after "
                          "its own (while each takes at least half its step); 0: a fresh factorization every "
                          "iteration", Range::closed(0, 1000));
  parameters::declare_int(jump, "descend after failures", d.jump.descend_after_failures,
                          "after this many failed step attempts in a row, try the energy descent at the last "
                          "failed load: an ordinary step if it releases no more than the step balance tolerance (a "
                          "small snap of the peel front), else bisect towards that load as before and try no early "
                          "descent until it is passed; only with 'past instabilities' = jump and a positive 'step "
                          "balance tolerance'; 0: never (bisect to the smallest increment, then jump)",
                          Range::closed(0, 100));
  parameters::declare_double(jump, "step balance tolerance", d.step_balance_tolerance,
                             "largest energy released by one converged load step, over Pi_c0: a step releasing more "
                             "crossed a snap (Newton landed on another branch) and is cut back, or at the smallest "
                             "increment counted as a jump; 0 switches the check off (scenes with adhesion only)",
                             Range::closed(0.0, 1.0));
  declare_stages(loading);
  auto& arc = parameters::declare_sublist(loading, "Arc Length", "LOCA arc-length steps (scaled norm)");
  const auto& a = d.arc_length_steps;
  parameters::declare_double(arc, "initial", a.initial, "first step", Range::positive());
  parameters::declare_double(arc, "minimum", a.minimum, "smallest step", Range::positive());
  parameters::declare_double(arc, "maximum", a.maximum, "largest step", Range::positive());
  parameters::declare_int(arc, "maximum steps", a.maximum_steps, "steps per fold", Range::closed(1, 100000));
}

LoadingParameters LoadingParameters::from(const Teuchos::ParameterList& loading)
{
  LoadingParameters p;
  p.type = parameters::choice<LoadingType>(loading, "type", loading_types());
  p.theta_y = loading.get<double>("theta_y");
  p.final_lift = loading.get<double>("final lift");
  p.free_lift = loading.get<bool>("free lift during rotation");
  p.free_slide = loading.get<bool>("free slide during lift");
  p.lift_relative = loading.get<bool>("final lift relative");
  p.hold_contact_surface = loading.get<bool>("hold contact surface");
  p.pull_angle = loading.get<double>("pull angle");
  p.rotation_steps = analysis::StepParameters::from(loading.sublist("Rotation Steps"), "Loading/Rotation Steps");
  p.lift_steps = analysis::StepParameters::from(loading.sublist("Lift Steps"), "Loading/Lift Steps");
  p.past_instabilities = loading.get<std::string>("past instabilities");
  p.restart_file = loading.get<std::string>("restart file");
  p.restart_theta_y = loading.get<double>("restart theta_y");
  p.restart_from_last_state = loading.get<std::string>("restart from") == "last state";
  if (p.restart_from_last_state && p.restart_file.empty())
    throw parameters::InputError("parameter 'Loading/restart from' = 'last state' needs 'Loading/restart file' (empty)");
  std::stringstream list(loading.get<std::string>("checkpoints at theta_y"));
  for (std::string item; std::getline(list, item, ',');) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(value) ||
        value < -180.0 || value > 180.0)
      throw parameters::InputError("parameter 'Loading/checkpoints at theta_y': '" +
                                   parameters::shorten(item) +
                                   "' is not an inclination in [-180, 180] deg");
    p.checkpoints.push_back(value);
  }
  std::sort(p.checkpoints.begin(), p.checkpoints.end());
  const auto& jump = loading.sublist("Jump");
  p.jump.maximum_iterations = jump.get<int>("maximum iterations");
  p.jump.method = parameters::choice<analysis::JumpParameters::Method>(jump, "method",
                                                                       analysis::JumpParameters::method_names());
  p.jump.trust_region_from = jump.get<int>("trust region from");
  p.jump.refactor = parameters::choice<analysis::JumpParameters::Refactor>(jump, "refactor",
                                                                           analysis::JumpParameters::refactor_names());
  p.jump.reused_factors = jump.get<int>("reused factors");
  p.jump.descend_after_failures = jump.get<int>("descend after failures");
  p.step_balance_tolerance = jump.get<double>("step balance tolerance");
  const auto& arc = loading.sublist("Arc Length");
  p.arc_length_steps.initial = arc.get<double>("initial");
  p.arc_length_steps.minimum = arc.get<double>("minimum");
  p.arc_length_steps.maximum = arc.get<double>("maximum");
  p.arc_length_steps.maximum_steps = arc.get<int>("maximum steps");
  p.stages = p.type == LoadingType::stages ? read_stages(loading.sublist("Stages")) : fixed_stages(p);
  return p;
}

}  // namespace spatula::app
