#pragma once
// The energy line search (energy_line_search.hpp) as a NOX line search, with the front's relaxation after a full
// step where `Front Elimination/use` asks for it.
#include "solvers/front_elimination.hpp"
#include "solvers/spatula_model.hpp"

#include <NOX_LineSearch_UserDefinedFactory.H>
#include <Teuchos_RCP.hpp>

namespace spatula::solvers {

// Its fallback, where the direction does not lower the energy or no admissible point is found: NOX's backtracking.
Teuchos::RCP<NOX::LineSearch::UserDefinedFactory> energy_line_search_factory(
    const SpatulaModel& model, const FrontEliminationParameters& elimination, EliminationCounts& counts);

}  // namespace spatula::solvers
