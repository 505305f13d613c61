#include "discretization/solid_model.hpp"

#include "laws/neo_hookean.hpp"
#include "parameters/parameter_validation.hpp"

namespace spatula::discretization {

void SolidParameters::declare(Teuchos::ParameterList& material)
{
  const SolidParameters d;   // the defaults
  using parameters::Range;
  parameters::declare_string(material, "law", d.law, "the solid's hyperelastic law (E and nu its parameters)",
                             SolidLawRegistry::instance().names());
  parameters::declare_double(material, "E", d.young, "Young's modulus [GPa]", Range::positive());
  parameters::declare_double(material, "nu", d.poisson, "Poisson's ratio", {-1.0, 0.5, true, true});
  parameters::declare_int(material, "quadrature order", d.quadrature_order,
                          "Gauss points per direction in each hexahedron",
                          Range::closed(1, 4));
}

SolidParameters SolidParameters::from(const Teuchos::ParameterList& material)
{
  SolidParameters p;
  p.law = material.get<std::string>("law");
  p.young = material.get<double>("E");
  p.poisson = material.get<double>("nu");
  p.quadrature_order = material.get<int>("quadrature order");
  return p;
}

SolidLawRegistry::SolidLawRegistry()
{
  // The compressible Neo-Hookean law of the paper (eq. 9), from E and nu.
  factories_["neo-hookean"] = [](const SolidParameters& p) {
    return std::make_shared<LawSolidModel<laws::NeoHookean>>("neo-hookean",
                                                             laws::NeoHookean::from_young(p.young, p.poisson), p);
  };
}

SolidLawRegistry& SolidLawRegistry::instance()
{
  static SolidLawRegistry registry;
  return registry;
}

void SolidLawRegistry::add(const std::string& name, Factory factory) { factories_[name] = std::move(factory); }

std::vector<std::string> SolidLawRegistry::names() const
{
  std::vector<std::string> names;
  for (const auto& entry : factories_) names.push_back(entry.first);
  return names;
}

std::shared_ptr<const SolidModel> SolidLawRegistry::make(const SolidParameters& parameters) const
{
  const auto found = factories_.find(parameters.law);
  if (found == factories_.end()) {
    std::string known;
    for (const auto& name : names()) known += (known.empty() ? "'" : ", '") + name + "'";
    throw parameters::InputError("parameter 'Material/law' = '" + parameters.law + "' is not a solid law; one of " +
                                 known);
  }
  return found->second(parameters);
}

}  // namespace spatula::discretization
