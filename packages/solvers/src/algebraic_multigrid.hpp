#pragma once
// Algebraic multigrid for the Newton tangents (Linear Solver/type = gmres-amg): MueLu smoothed aggregation on a copy
// of the tangent padded to 3 x 3 node blocks (solvers::NodeBlocks: the rows smoothed aggregation amalgamates
// into nodes), with the six rigid-body modes as near-null space and Chebyshev smoothing. The masters' block is kept
// to its diagonal (its dense couplings to the end face's neighbours are left to GMRES: a difference of rank at most
// 6). The hierarchy is built on the first tangent and reused by the later ones (prolongators kept, coarse operators
// and smoothers rebuilt). A tangent whose solves took `stall_applications` V-cycles or more (a GMRES that ran to its
// iteration limit: an indefinite tangent past a fold, a pad too thin for the aggregation) hands every later tangent
// to the fallback (MUMPS).
#include "solvers/node_blocks.hpp"

#include <Thyra_PreconditionerFactoryBase.hpp>

#include <memory>

namespace spatula::solvers {

struct MultigridStatistics {
  int setups = 0;            // hierarchies built
  int reuses = 0;            // tangents that reused one
  long applications = 0;     // preconditioner applications (one per GMRES iteration, one more per restart cycle)
  bool fell_back = false;    // a solve stalled: the fallback serves every later tangent
};

class AlgebraicMultigrid {
public:
  AlgebraicMultigrid(std::shared_ptr<const NodeBlocks> blocks, int stall_applications);
  ~AlgebraicMultigrid();

  // A Thyra preconditioner factory over this hierarchy (Stratimikos makes one per linear solver it builds).
  Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>>
  preconditioner_factory(Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>> fallback) const;
  const MultigridStatistics& statistics() const;

  struct State;

private:
  std::shared_ptr<State> state_;
};

}  // namespace spatula::solvers
