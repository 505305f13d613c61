#pragma once
// The XML "Adhesion/Friction" sublist: the adhesive friction law's sliding limit, its constants and its elastic
// stick (adhesive_friction.hpp), read into an AdhesiveFriction over the scene's Lennard-Jones law. Used by the
// 'Adhesion/law' = adhesive friction.
#include "contact/adhesive_friction.hpp"

#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

namespace spatula::contact {

const std::vector<std::string>& sliding_limit_names();   // in the order of AdhesiveFriction::Limit

void declare_friction(Teuchos::ParameterList& adhesion);
// Reads the validated sublist 'Friction' of `adhesion`; `law` is the scene's normal law.
AdhesiveFriction read_friction(const Teuchos::ParameterList& adhesion, const LennardJones& law);

}  // namespace spatula::contact
