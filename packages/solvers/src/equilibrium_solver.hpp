#pragma once
// The equilibrium solver of a load step: from a trial state at the current load to a converged state, or a diagnosis
// of why not. NewtonSolver (newton.hpp: NOX's line-search Newton with the energy line search) is the one the load
// path uses; another method (a local treatment of the peel front, a minimizer) is added behind this interface
// without an edit to analysis::LoadPath.
#include "discretization/tpetra_types.hpp"
#include "solvers/front_elimination.hpp"
#include "solvers/linear_solver.hpp"

#include <ostream>
#include <string>
#include <vector>

namespace spatula::solvers {

struct NewtonIteration {
  int iteration = 0;
  double residual_norm = 0.0;
  double update_norm = 0.0;
  double step = 1.0;
  int negative_pivots = -1;
  double seconds = 0.0;
  // f(x_k) . dx / f(x_k-1) . dx: the energy's slope along the step at its end over its slope at its start (0: the
  // step ended at the minimum along its line; < 0: past it; > 0 and near 1: far short of it).
  double slope_ratio = 0.0;
};

struct NewtonResult {
  bool converged = false;
  std::string failure;   // why not, for the log
  double initial_residual_norm = 0.0;
  std::vector<NewtonIteration> iterations;
  EliminationCounts elimination;
};

class EquilibriumSolver {
public:
  virtual ~EquilibriumSolver() = default;
  // Solves f(x) = 0 starting from x; on success x holds the solution, otherwise x is unchanged. `table`: the
  // iterations' convergence table, if wanted. `after_failure`: the caller retries after a failed step (a fold may be
  // near), where a solver may give up early on a hopeless try.
  virtual NewtonResult solve(discretization::Vector& x, std::ostream* table, bool after_failure = false) const = 0;
  // The linear solver its steps use (the jump's energy descent factors with the same MUMPS options).
  virtual const LinearSolverFactory& linear_solver() const = 0;
};

}  // namespace spatula::solvers
