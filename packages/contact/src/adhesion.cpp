#include "contact/adhesion.hpp"

#include "contact/contact_registry.hpp"
#include "contact/friction_parameters.hpp"
#include "discretization/discrete_system.hpp"
#include "parameters/parameter_validation.hpp"

#include <cmath>

namespace spatula::contact {

namespace {

constexpr double pi = 3.14159265358979323846;

}  // namespace

double AdhesionSettings::gamma_W(double young) const
{
  const double r0 = lennard_jones.r0;
  return young / (lennard_jones.hamaker / (2.0 * pi * pi * r0 * r0 * r0));
}

void AdhesionParameters::declare(Teuchos::ParameterList& adhesion)
{
  using parameters::Range;
  const AdhesionParameters d;   // the defaults
  const auto& s = d.settings;
  std::vector<std::string> laws{"none"};
  for (const auto& name : ContactLawRegistry::instance().names()) laws.push_back(name);
  parameters::declare_string(adhesion, "law", d.enabled ? s.law : "none",
                             "van der Waals adhesion law (none: no contact)", laws);
  parameters::declare_string(adhesion, "substrate", parameters::name_of(s.substrate, substrate_names()),
                             "rigid substrate", substrate_names());
  parameters::declare_string(adhesion, "enrichment",
                             parameters::name_of(s.enrichment, discretization::enrichment_names()),
                             "contact surface interpolation: Q1C1 bilinear, Q1C2 biquadratic",
                             discretization::enrichment_names());
  parameters::declare_int(adhesion, "quadrature", s.quadrature, "Gauss points per direction on each contact element",
                          Range::closed(1, 8));
  parameters::declare_string(adhesion, "specification", "physical",
                             "physical: A_H and r0; normalized: gamma_W and gamma_L (R0 = 1 nm, W0 = E)",
                             {"physical", "normalized"});
  parameters::declare_double(adhesion, "A_H", 10.0 * s.lennard_jones.hamaker, "Hamaker constant [1e-19 J]",
                             Range::positive());
  parameters::declare_double(adhesion, "r0", s.lennard_jones.r0, "Lennard-Jones length [nm]", Range::positive());
  // The normalized form of the same constants, at the default Young's modulus (25.266 and 2.5).
  const double gamma_W = s.gamma_W(discretization::SolidParameters{}.young);
  parameters::declare_double(adhesion, "gamma_W", std::round(1000.0 * gamma_W) / 1000.0,
                             "E / w0, w0 = A_H / (2 pi^2 r0^3)", Range::positive());
  parameters::declare_double(adhesion, "gamma_L", s.gamma_L(), "R0 / r0 with R0 = 1 nm", Range::positive());
  parameters::declare_double(adhesion, "regularization", 0.8,
                             "r_reg / r_eq: below r_reg the traction continues linearly (C1)", {0.0, 1.0, true, false});
  parameters::declare_double(adhesion, "cut-off", 10.0, "gap beyond which the traction is neglected [nm]",
                             Range::positive());
  parameters::declare_bool(adhesion, "skip distant faces", s.skip_distant_faces,
                           "leave out faces whose every point is beyond the cut-off (false: integrate every face; "
                           "for measuring what the skip saves)");
  parameters::declare_string(adhesion, "stiction anchors", s.anchor_at_restart ? "restart state" : "undeformed",
                             "where the stiction law measures a point's tangential travel from, and where adhesive "
                             "friction's points start unstrained (their history cleared): the undeformed spatula, or "
                             "the state the run restarts from ('Loading/restart file'; the "
                             "paper's Fig. 9 switches stiction on for the pull-off from the pre-rotated state)",
                             {"undeformed", "restart state"});
  declare_friction(adhesion);
  auto& rough = parameters::declare_sublist(adhesion, "Rough Substrate", "Gaussian asperities on a triangular grid");
  parameters::declare_double(rough, "z0", s.rough.z0, "asperity height [nm]", Range::non_negative());
  parameters::declare_double(rough, "h", s.rough.width, "asperity width [nm]", Range::positive());
  parameters::declare_double(rough, "lambda", s.rough.spacing, "grid spacing [nm]", Range::positive());
  parameters::declare_bool(rough, "conform initially", s.conform,
                           "start from the pad pressed onto the substrate (each column of nodes shifted so the bottom "
                           "sits at the equilibrium gap over the surface), then find equilibrium");
}

AdhesionParameters AdhesionParameters::from(const Teuchos::ParameterList& adhesion, double young)
{
  AdhesionParameters p;
  const auto law = adhesion.get<std::string>("law");
  p.enabled = law != "none";
  auto& s = p.settings;
  s.law = law;
  s.substrate = parameters::choice<SubstrateKind>(adhesion, "substrate", substrate_names());
  s.enrichment =
      parameters::choice<discretization::Enrichment>(adhesion, "enrichment", discretization::enrichment_names());
  s.quadrature = adhesion.get<int>("quadrature");
  s.skip_distant_faces = adhesion.get<bool>("skip distant faces");
  s.anchor_at_restart = adhesion.get<std::string>("stiction anchors") == "restart state";
  auto& lj = s.lennard_jones;
  if (adhesion.get<std::string>("specification") == "physical") {
    lj.hamaker = 0.1 * adhesion.get<double>("A_H");   // 1e-19 J = 0.1 nN nm
    lj.r0 = adhesion.get<double>("r0");
  } else {
    lj.r0 = 1.0 / adhesion.get<double>("gamma_L");
    lj.hamaker = 2.0 * pi * pi * std::pow(lj.r0, 3) * young / adhesion.get<double>("gamma_W");
  }
  const double r_eq = lj.equilibrium_gap();
  lj.r_reg = adhesion.get<double>("regularization") * r_eq;
  lj.r_cut = adhesion.get<double>("cut-off");
  if (lj.r_cut <= 2.0 * lj.r0)
    parameters::fail("Adhesion/cut-off", lj.r_cut, "must exceed 2 r0 = " + std::to_string(2.0 * lj.r0) +
                                                        " nm (the attraction reaches further)");
  s.substrate_height = -r_eq;
  s.friction = read_friction(adhesion, lj);
  const auto& rough = adhesion.sublist("Rough Substrate");
  s.rough.z0 = rough.get<double>("z0");
  s.rough.width = rough.get<double>("h");
  s.rough.spacing = rough.get<double>("lambda");
  s.rough.base = -r_eq - s.rough.z0;   // asperity tops at the pad's equilibrium gap
  s.conform = rough.get<bool>("conform initially");
  if (p.enabled) p.model = make_contact_model(s);   // checks the law/substrate combination now, before anything runs
  return p;
}

std::shared_ptr<const discretization::ContactModel> make_contact_model(const AdhesionSettings& settings)
{
  return ContactLawRegistry::instance().create(settings);
}

}  // namespace spatula::contact
