#include "loading.hpp"

#include "parameter_validation.hpp"

namespace spatula::app {

const std::vector<std::string>& loading_types()
{
  static const std::vector<std::string> types = {"none", "rotation", "lift"};
  return types;
}

void LoadingParameters::declare(Teuchos::ParameterList& loading)
{
  using parameters::Range;
  parameters::declare_string(loading, "type", "none",
                             "none: mesh only; rotation: rotate the end face to theta_y; lift: rotate to theta_y, "
                             "then raise the face to 'final lift'",
                             loading_types());
  parameters::declare_double(loading, "theta_y", 30.0, "shaft inclination to reach (rotation) or hold (lift) [deg]",
                             Range::closed(-180.0, 180.0));
  parameters::declare_double(loading, "final lift", 100.0, "u_z of the end face centre at the end of a lift [nm]",
                             Range::closed(-1e4, 1e4));
  parameters::declare_bool(loading, "free lift during rotation", true,
                           "zero net Z force on the end face while rotating (false: u_z held at 0)");
  parameters::declare_bool(loading, "hold contact surface", false,
                           "hold the pad's contact surface at Z = 0 (a structural check without adhesion)");
  analysis::StepParameters::declare(
      parameters::declare_sublist(loading, "Rotation Steps", "increments of theta_y [deg]"), 1.0, 1e-3, 5.0);
  analysis::StepParameters::declare(
      parameters::declare_sublist(loading, "Lift Steps", "increments of u_z [nm]"), 2.0, 1e-3, 10.0);
}

LoadingParameters LoadingParameters::from(const Teuchos::ParameterList& loading)
{
  LoadingParameters p;
  p.type = loading.get<std::string>("type");
  p.theta_y = loading.get<double>("theta_y");
  p.final_lift = loading.get<double>("final lift");
  p.free_lift = loading.get<bool>("free lift during rotation");
  p.hold_contact_surface = loading.get<bool>("hold contact surface");
  p.rotation_steps = analysis::StepParameters::from(loading.sublist("Rotation Steps"), "Loading/Rotation Steps");
  p.lift_steps = analysis::StepParameters::from(loading.sublist("Lift Steps"), "Loading/Lift Steps");
  return p;
}

}  // namespace spatula::app
