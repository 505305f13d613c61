#pragma once
// Splits a mesh over MPI ranks by recursive coordinate bisection of the element centroids. Every rank builds the
// same (deterministic) serial mesh and keeps its global numbering; the partition decides which rank assembles
// which elements and owns which nodes, so results do not depend on the rank count.
#include "mesh/hex_mesh.hpp"

#include <vector>

namespace spatula::mesh {

struct Partition {
  int ranks = 1;
  std::vector<int> element_owner;   // rank assembling each element
  std::vector<int> node_owner;      // lowest rank among the elements sharing the node

  // Elements and nodes of one rank: `owned_nodes` first, then the `shared_nodes` owned elsewhere but
  // touched by the rank's elements (sorted by global id within each group).
  std::vector<std::int64_t> elements_of(int rank) const;
  std::vector<std::int64_t> owned_nodes_of(int rank) const;
  std::vector<std::int64_t> shared_nodes_of(int rank, const HexMesh& mesh) const;
};

Partition partition_mesh(const HexMesh& mesh, int ranks);

}  // namespace spatula::mesh
