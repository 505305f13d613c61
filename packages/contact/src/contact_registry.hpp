#pragma once
// Registry of contact laws: a name usable in XML ("Adhesion/law") -> a factory building the device contact model
// for the chosen substrate. Built in: "frictionless" (flat and rough substrates), "stiction" and "adhesive friction"
// (flat; friction_integrand.hpp, a law with history and a non-symmetric tangent). A new law is
// a device integrand (see elements/contact_face.hpp) plus one `add` call; nothing else changes.
#include "contact/adhesion.hpp"

#include <functional>
#include <map>
#include <vector>

namespace spatula::contact {

using ContactFactory =
    std::function<std::shared_ptr<const discretization::ContactModel>(const AdhesionSettings& settings)>;

class ContactLawRegistry {
public:
  static ContactLawRegistry& instance();
  void add(const std::string& name, ContactFactory factory);
  std::shared_ptr<const discretization::ContactModel> create(const AdhesionSettings& settings) const;
  std::vector<std::string> names() const;

private:
  ContactLawRegistry();
  std::map<std::string, ContactFactory> factories_;
};

const std::vector<std::string>& substrate_names();   // "flat", "rough"

}  // namespace spatula::contact
