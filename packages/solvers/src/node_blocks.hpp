#pragma once
// The displacement unknowns padded to three rows per node, the form smoothed aggregation works on: every node with
// an unknown gets a block of three rows (a fixed component a row of its own, with no unknown behind it), and the
// three masters one more block. Each block lives on the rank owning the node's unknowns.
#include "discretization/discrete_system.hpp"

#include <vector>

namespace spatula::solvers {

struct NodeBlocks {
  Teuchos::RCP<const discretization::Map> map;                   // the padded rows this rank owns
  std::vector<discretization::GlobalOrdinal> row_of_unknown;     // per global unknown, its padded row (every rank)
  discretization::GlobalOrdinal master_block = 0;                // the first padded row of the masters' block
  // On `map`: the six rigid-body motions (translations along X, Y, Z, rotations about X, Y, Z through the
  // centroid of the node space) at the nodes' rows, zero in the masters' block: the near-null space of elasticity.
  Teuchos::RCP<discretization::MultiVector> rigid_body_modes;
};

// The unknowns of `system` in node blocks. Collective.
NodeBlocks node_blocks(const discretization::DiscreteSystem& system);

}  // namespace spatula::solvers
