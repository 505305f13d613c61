#include "contact/contact_registry.hpp"

#include "contact/contact_kernel.hpp"
#include "contact/friction_integrand.hpp"
#include "contact/friction_parameters.hpp"
#include "parameters/parameter_validation.hpp"

namespace spatula::contact {

const std::vector<std::string>& substrate_names()
{
  static const std::vector<std::string> names = {"flat", "rough"};
  return names;
}

namespace {

// The model's description; `law_details` is what the law's own factory adds.
std::string describe(const AdhesionSettings& s, const std::string& law_details = "")
{
  return s.law + " Lennard-Jones adhesion on a " + parameters::name_of(s.substrate, substrate_names()) + " substrate (A_H = " +
         std::to_string(s.lennard_jones.hamaker * 10.0) + "e-19 J, r0 = " + std::to_string(s.lennard_jones.r0) +
         " nm, r_reg = " + std::to_string(s.lennard_jones.r_reg) + " nm, r_cut = " +
         std::to_string(s.lennard_jones.r_cut) + " nm), " +
         parameters::name_of(s.enrichment, discretization::enrichment_names()) + ", " + std::to_string(s.quadrature) +
         "x" + std::to_string(s.quadrature) + " points per face" +
         (s.skip_distant_faces ? "" : ", every face integrated") + law_details;
}

std::shared_ptr<const discretization::ContactModel> frictionless(const AdhesionSettings& s)
{
  const double w = s.lennard_jones.work_of_adhesion();
  if (s.substrate == SubstrateKind::flat) {
    contact::FrictionlessIntegrand<contact::FlatSubstrate> integrand{s.lennard_jones, {s.substrate_height}};
    return std::make_shared<IntegrandContactModel<decltype(integrand)>>(integrand, s.quadrature, describe(s), w,
                                                                        s.skip_distant_faces);
  }
  contact::FrictionlessIntegrand<contact::RoughSubstrate> integrand{s.lennard_jones, s.rough};
  return std::make_shared<IntegrandContactModel<decltype(integrand)>>(integrand, s.quadrature, describe(s), w,
                                                                        s.skip_distant_faces);
}

std::shared_ptr<const discretization::ContactModel> stiction(const AdhesionSettings& s)
{
  if (s.substrate != SubstrateKind::flat)
    throw parameters::InputError("parameter 'Adhesion/law' = 'stiction' needs 'Adhesion/substrate' = 'flat' (got '" +
                                 parameters::name_of(s.substrate, substrate_names()) +
                                 "'): tangential travel on a curved substrate is not defined");
  contact::StictionIntegrand integrand{{s.lennard_jones, s.substrate_height}};
  const std::string anchors = s.anchor_at_restart ? ", travel measured from the restart state"
                                                  : ", travel measured from the undeformed state";
  return std::make_shared<IntegrandContactModel<decltype(integrand)>>(integrand, s.quadrature, describe(s, anchors),
                                                                      s.lennard_jones.work_of_adhesion(),
                                                                      s.skip_distant_faces);
}

std::shared_ptr<const discretization::ContactModel> adhesive_friction(const AdhesionSettings& s)
{
  if (s.substrate != SubstrateKind::flat)
    throw parameters::InputError("parameter 'Adhesion/law' = 'adhesive friction' needs 'Adhesion/substrate' = 'flat' "
                                 "(got '" + parameters::name_of(s.substrate, substrate_names()) +
                                 "'): sliding along a curved substrate is not defined");
  const auto& f = s.friction;
  if (f.limit == AdhesiveFriction::Limit::constant_strength && f.strength <= 0.0)
    parameters::fail("Adhesion/Friction/strength", f.strength,
                     "must be positive with 'sliding limit' = 'constant strength' (else the law is frictionless)");
  contact::AdhesiveFrictionIntegrand integrand{{s.lennard_jones, {s.substrate_height}}, f};
  const std::string limit =
      f.limit == AdhesiveFriction::Limit::extended_amontons
          ? "extended Amontons limit mu (T_n + t_max), mu = " + std::to_string(f.coefficient)
          : "constant strength tau_0 = " + std::to_string(f.strength) + " nN/nm^2";
  return std::make_shared<IntegrandContactModel<decltype(integrand)>>(
      integrand, s.quadrature,
      describe(s, ", sliding on the " + limit + " within g_c = " + std::to_string(f.cutoff) + " nm, stick stiffness " +
                      std::to_string(f.stiffness) + " nN/nm^3" +
                      (f.frozen        ? ", variational update on the committed limit"
                       : f.variational ? ", variational update"
                                       : "")),
      s.lennard_jones.work_of_adhesion(), s.skip_distant_faces);
}

}  // namespace

ContactLawRegistry::ContactLawRegistry()
{
  factories_["frictionless"] = frictionless;
  factories_["stiction"] = stiction;
  factories_["adhesive friction"] = adhesive_friction;
}

ContactLawRegistry& ContactLawRegistry::instance()
{
  static ContactLawRegistry registry;
  return registry;
}

void ContactLawRegistry::add(const std::string& name, ContactFactory factory) { factories_[name] = std::move(factory); }

std::shared_ptr<const discretization::ContactModel> ContactLawRegistry::create(const AdhesionSettings& settings) const
{
  const auto it = factories_.find(settings.law);
  if (it == factories_.end()) {
    std::string allowed;
    for (const auto& name : names()) allowed += (allowed.empty() ? "" : ", ") + name;
    throw parameters::InputError("parameter 'Adhesion/law' = '" + settings.law + "' is not registered; allowed: " +
                                 allowed);
  }
  return it->second(settings);
}

std::vector<std::string> ContactLawRegistry::names() const
{
  std::vector<std::string> names;
  for (const auto& entry : factories_) names.push_back(entry.first);
  return names;
}

}  // namespace spatula::contact
