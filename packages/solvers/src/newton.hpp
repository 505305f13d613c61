#pragma once
// Newton's method with a line search (NOX, line-search based solver over the Thyra model), converging when
//   (|f|_2 <= absolute tolerance  or  |f|_2 <= relative tolerance * |f_0|_2)  and  |dx|_inf <= update tolerance,
// and a convergence table per step: iteration, residual norm, update norm, line-search step, negative pivots of
// the tangent (MUMPS LDL^T inertia), seconds, slope ratio (below).
#include "solvers/equilibrium_solver.hpp"
#include "solvers/front_elimination.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/spatula_model.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace spatula::solvers {

enum class LineSearch { backtrack, polynomial, full_step, energy };   // in the order of line_search_names()

struct NewtonParameters {
  double relative_tolerance = 1e-9;
  double absolute_tolerance = 1e-5;    // [nN] (scaled norms: the RMS nodal force, 1e-5 nN = 10 fN)
  double update_tolerance = 1e-6;      // [nm] (and rad for the rotation)
  int maximum_iterations = 12;
  int converging_extension = 8;        // ... more while each of the last two iterations cut |f| by `contraction`
  LineSearch line_search = LineSearch::energy;
  bool scaled_norms = true;                // tolerances on |f|_2 / sqrt(n) and |dx|_inf / n (NOX's default)
  bool inexact = true;                     // Eisenstat-Walker forcing terms for the linear solves
  int non_contracting_iterations = 2;      // give up after this many iterations with |f_k| >= contraction |f_k-1|
  bool give_up_only_after_failure = true;  // ... only in attempts made after a step failed (near a fold)
  double contraction = 0.5;
  // The give-up rules count an iteration only while |f| is above this multiple of the absolute tolerance: nearer
  // it an attempt is converging, however slowly (on the fine mesh Newton near a fold stalls at |f| a few times the
  // tolerance, and giving up there sent the path into energy descents that stayed on the branch). 0: any |f|.
  double give_up_above_tolerance = 10.0;
  // Give up on any attempt (the first too) once the line search has cut the step to at most `short_step` in
  // `short_steps` iterations in a row while |f| is still above 1e-3 of its first value: Newton's direction is no
  // use there (past a fold, an indefinite tangent). 0: off.
  int short_steps = 2;
  double short_step = 0.125;
  FrontEliminationParameters elimination;   // the sublist "Front Elimination"
  // With a convergence table: under each iteration's row, the contact points its full step carries across the law's
  // inflection and the energy along that step (front_diagnosis.hpp; five more evaluations per iteration).
  bool front_diagnosis = false;

  static void declare(Teuchos::ParameterList& list);
  static NewtonParameters from(const Teuchos::ParameterList& list);
};

const std::vector<std::string>& line_search_names();

class NewtonSolver : public EquilibriumSolver {
public:
  NewtonSolver(Teuchos::RCP<SpatulaModel> model, const NewtonParameters& parameters,
               const LinearSolverFactory& linear_solver);
  // Solves f(x) = 0 starting from x; on success x holds the solution, otherwise x is unchanged. `after_failure`:
  // the caller retries after a failed step (a fold may be near), where the give-up rule applies by default.
  NewtonResult solve(discretization::Vector& x, std::ostream* table, bool after_failure = false) const override;

  const LinearSolverFactory& linear_solver() const override { return linear_solver_; }

private:
  Teuchos::RCP<SpatulaModel> model_;
  NewtonParameters parameters_;
  const LinearSolverFactory& linear_solver_;
};

}  // namespace spatula::solvers
