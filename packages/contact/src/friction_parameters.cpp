#include "contact/friction_parameters.hpp"

#include "parameters/parameter_validation.hpp"

namespace spatula::contact {

const std::vector<std::string>& sliding_limit_names()
{
  static const std::vector<std::string> names = {"extended Amontons", "constant strength"};
  return names;
}

void declare_friction(Teuchos::ParameterList& adhesion)
{
  using parameters::Range;
  const AdhesiveFriction d;
  auto& friction = parameters::declare_sublist(
      adhesion, "Friction",
      "the adhesive friction law's (Mergel, Sahli, Scheibert and Sauer 2019): elastic stick, then sliding on a limit "
      "that acts in tension too; used by 'law' = adhesive friction");
  parameters::declare_string(friction, "sliding limit", parameters::name_of(d.limit, sliding_limit_names()),
                             "extended Amontons: mu (T_n + t_max), growing with the normal traction from zero at "
                             "the strongest attraction; constant strength: tau_0 within the cut-off gap",
                             sliding_limit_names());
  parameters::declare_double(friction, "coefficient", d.coefficient, "mu of the extended Amontons limit",
                             Range::non_negative());
  parameters::declare_double(friction, "strength", 0.037,
                             "tau_0 of the constant-strength limit [nN/nm^2] (0.037: mu t_max of the default "
                             "Lennard-Jones constants with mu = 0.3)",
                             Range::non_negative());
  parameters::declare_double(friction, "stiffness", d.stiffness,
                             "eps_T, the elastic stick's tangential stiffness per unit area [nN/nm^3]",
                             Range::positive());
  parameters::declare_string(friction, "update", d.variational ? "variational" : "return mapping",
                             "return mapping: the sliding law as published (its tangent not symmetric; a jump's "
                             "descent minimizes the frozen limit's energy, Newton confirming its state with the "
                             "return mapping, or where it cannot with the frozen limit); variational: "
                             "each step minimizes its incremental energy (the normal traction gains tau'(g) times the "
                             "step's slip, which vanishes with the step; a symmetric tangent, an energy the line "
                             "search and the jumps' descents can use); frozen limit: the same with each step sliding "
                             "on the limit of its committed state (no tau' term: a jump's slip is charged at the "
                             "limit it started from)",
                             {"return mapping", "variational", "frozen limit"});
  parameters::declare_double(friction, "cut-off", d.cutoff,
                             "gap g_c up to which the limit acts in full; it fades to zero at 1.25 g_c [nm]",
                             Range::positive());
}

AdhesiveFriction read_friction(const Teuchos::ParameterList& adhesion, const LennardJones& law)
{
  const auto& list = adhesion.sublist("Friction");
  AdhesiveFriction friction;
  friction.law = law;
  friction.limit = parameters::choice<AdhesiveFriction::Limit>(list, "sliding limit", sliding_limit_names());
  friction.coefficient = list.get<double>("coefficient");
  friction.strength = list.get<double>("strength");
  friction.stiffness = list.get<double>("stiffness");
  friction.cutoff = list.get<double>("cut-off");
  const auto update = list.get<std::string>("update");
  friction.variational = update != "return mapping";
  friction.frozen = update == "frozen limit";
  if (1.25 * friction.cutoff > 0.5 * law.r_cut)
    parameters::fail("Adhesion/Friction/cut-off", friction.cutoff,
                     "must be at most 0.4 'Adhesion/cut-off' = " + std::to_string(0.4 * law.r_cut) +
                         " nm: the friction acts where the Lennard-Jones law is not yet blended out");
  return friction;
}

}  // namespace spatula::contact
