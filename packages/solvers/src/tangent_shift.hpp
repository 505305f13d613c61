#pragma once
// The energy descent's proximal shift: K + eta I, the tangent of Pi(x) + eta/2 |x - x_k|^2 at its anchor x_k (where
// the residual is unchanged), added to the assembled tangent on every owned row but the prescribed masters'
// identity rows. The minimizer applies it to the tangent it factors; the discrete system knows nothing of it.
#include "discretization/discrete_system.hpp"

namespace spatula::solvers {

// Adds eta to the diagonal of system.jacobian() (assembled at a state, as evaluate() left it). Collective: none.
void shift_tangent(discretization::DiscreteSystem& system, double eta);

}  // namespace spatula::solvers
