#pragma once
// The eigenvalue of a symmetric tangent nearest zero, by inverse iteration on its own LDL^T factors: how close a
// converged state is to a limit point (a fold of the load path, where that eigenvalue vanishes), and how localized
// its mode is. A diagnosis of slow Newton convergence, not part of the solution (Output/tangent spectrum).
#include "discretization/tpetra_types.hpp"
#include "solvers/mumps_solver.hpp"

namespace spatula::analysis {

struct NearestEigenvalue {
  double value = 0.0;           // the Rayleigh quotient y^T K y of the converged unit vector y [nN/nm]
  double relative = 0.0;        // value over the mean diagonal of K
  double residual = 0.0;        // |K y - value y| / |value|: the estimate's accuracy
  double participation = 0.0;   // (sum y_i^2)^2 / (n sum y_i^4): 1 for a mode spread over all unknowns, 1/n for one
  int negative_pivots = 0;      // of K's factors (its inertia)
};

// `solver` (LDL^T, on K's row map) is factored here; `iterations` solves from a start vector fixed by the unknowns'
// global numbers (the same on any number of ranks). Collective.
NearestEigenvalue nearest_eigenvalue(const discretization::CrsMatrix& tangent, solvers::MumpsSolver& solver,
                                     int iterations, double mean_diagonal);

}  // namespace spatula::analysis
