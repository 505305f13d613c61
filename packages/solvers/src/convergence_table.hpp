#pragma once
// The convergence table of a Newton solve: one row per iteration (|f|, |dx|, the line search's step, negative
// pivots, time, slope ratio), recorded in the solve's result and written to a stream; with a diagnosed model, a line
// under each row on the contact points the full step carries across the law's inflection (front_diagnosis.hpp).
#include "solvers/equilibrium_solver.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/spatula_model.hpp"

#include <NOX_Observer.hpp>
#include <Teuchos_RCP.hpp>

#include <iosfwd>

namespace spatula::solvers {

// `table`: where the rows go (none: recorded only); `diagnosed`: the model whose full steps are diagnosed (none:
// no diagnosis).
Teuchos::RCP<NOX::Observer> convergence_table(NewtonResult& result, const LinearSolverFactory& linear,
                                              std::ostream* table, const SpatulaModel* diagnosed);

}  // namespace spatula::solvers
