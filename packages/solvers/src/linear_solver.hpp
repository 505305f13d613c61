#pragma once
// Linear solvers for the Newton steps, chosen by name in XML and built through Stratimikos:
//
//   mumps      MUMPS LDL^T (or LU) direct solve, wrapped as the preconditioner of Belos GMRES (with fresh
//              double-precision factors GMRES converges in one iteration and refines the direct solution; with the
//              default single-precision factors flexible GMRES takes a few); correct on any number of ranks.
//              With `lag` > 0 a factorization is kept as the preconditioner of the following Newton tangents (GMRES
//              then needs a few iterations instead of one) until the solves it serves take more than
//              `lag applications` preconditioner applications, or `lag` tangents have passed: the Newton
//              directions stay exact (GMRES converges to the tolerance), only the factorizations are saved.
//              With `refactor` = cost the decision is made from the modelled work instead (RenewalRule, renewal_rule.hpp): a
//              factorization is kept while the last tangent's solves cost less than the average cost per tangent of
//              the current factorization's cycle (its factorization plus all the solves it served, over its
//              tangents); that keeps the long-run cost per tangent near its minimum whatever the mesh size. The work
//              is counted from MUMPS' own operation counts, not measured: the same scene takes the same path on a
//              quiet and a busy machine. `refactor` = clock decides from measured seconds (it follows the machine,
//              so a busy machine changes the path).
//   gmres-ilu  Belos GMRES with Ifpack2 ILU(k) of each rank's rows (block Jacobi across ranks).
//   gmres-amg  Belos GMRES with MueLu smoothed aggregation (algebraic_multigrid.hpp), its hierarchy reused across
//              tangents; after a tangent whose solves took `maximum iterations` V-cycles, MUMPS serves the later ones.
//   auto       mumps where its factors fit in the memory available, else gmres-amg (chosen by the app).
//
// The MUMPS factorization object lives as long as the factory, so its symbolic analysis is reused by every
// Newton iteration and load step.
#include "solvers/algebraic_multigrid.hpp"
#include "solvers/mumps_solver.hpp"

#include <Teuchos_ParameterList.hpp>
#include <Thyra_LinearOpWithSolveFactoryBase.hpp>

#include <string>
#include <vector>

namespace spatula::solvers {

// The linear solver of the Newton steps, in the order of linear_solver_names().
// `automatic` is resolved before a factory is made (the app picks from the memory the mesh needs).
enum class LinearSolverType { mumps, gmres_ilu, gmres_amg, automatic };

// When a kept MUMPS factorization is replaced by a new one (cost and clock: the renewal rule, renewal_rule.hpp).
enum class RefactorRule { lag, cost, clock };
const std::vector<std::string>& refactor_rule_names();   // in the order of RefactorRule

// The modelled work of refactor = cost, in factorization flops: a factorization costs its operation count
// (MUMPS' RINFOG(3)); a solve the operations of a forward and a backward substitution through the factors, weighted
// by how much dearer a substitution's operation is than a factorization's (memory-bound against BLAS-3).
struct FactorWork {
  static double factorization(const MumpsStatistics& statistics) { return statistics.factorization_flops; }
  static double solve(const MumpsStatistics& statistics, bool symmetric);
};

struct LinearSolverParameters {
  LinearSolverType type = LinearSolverType::mumps;
  double tolerance = 1e-10;     // relative residual of each linear solve
  int maximum_iterations = 500; // Krylov iterations (gmres-ilu, gmres-amg)
  int fill_level = 1;           // ILU(k) level of fill (gmres-ilu)
  // The Newton tangents' factors: MUMPS' defaults but single precision (a preconditioner of flexible GMRES, which
  // keeps the directions' tolerance; measured in docs/performance.md, "The peel front's cases").
  MumpsParameters mumps = [] {
    MumpsParameters newton;
    newton.single_precision = true;
    return newton;
  }();
  // With refactor = lag: tangents a MUMPS factorization may serve as preconditioner (0: refactor always; what 4 saves
  // against 0: docs/error-vs-time.md).
  int lag = 4;
  int lag_applications = 8;     // refactor once a tangent's solves needed more applications than this
  RefactorRule refactor = RefactorRule::cost;   // lag: the two limits above; cost: modelled work; clock: seconds

  static void declare(Teuchos::ParameterList& list);
  static LinearSolverParameters from(const Teuchos::ParameterList& list);
};

const std::vector<std::string>& linear_solver_names();

class LinearSolverFactory {
public:
  // node_blocks: the unknowns in node blocks (solvers::node_blocks); gmres-amg needs them.
  explicit LinearSolverFactory(const LinearSolverParameters& parameters,
                               std::shared_ptr<const NodeBlocks> node_blocks = nullptr);
  ~LinearSolverFactory();

  Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> lows_factory() const;
  // Statistics of the MUMPS factorizations (all zero for iterative solvers until gmres-amg falls back to MUMPS).
  const MumpsStatistics& mumps_statistics() const;
  // gmres-amg: hierarchies built, reused, preconditioner applications, and whether MUMPS has taken over.
  const MultigridStatistics& multigrid_statistics() const;
  const LinearSolverParameters& parameters() const;
  // The next tangent is factored afresh, whatever the refactor rule says. Call (on every rank) when the constrained
  // rows change (a master prescribed or freed): factors of the old ones, kept as GMRES' preconditioner, would let
  // a prescribed unknown move by the linear solve's tolerance at every Newton iteration.
  void renew_factors() const;

private:
  struct Implementation;
  std::unique_ptr<Implementation> implementation_;
};

}  // namespace spatula::solvers
