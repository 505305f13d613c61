#include "solvers/node_blocks.hpp"

#include <algorithm>

namespace spatula::solvers {

using discretization::GlobalOrdinal;
using discretization::LocalOrdinal;
using discretization::Map;
using discretization::MultiVector;

NodeBlocks node_blocks(const discretization::DiscreteSystem& system)
{
  const auto& layout = system.layout();
  const auto& space = system.nodes();
  const auto& coordinates = space.coordinates;
  const auto comm = system.owned_map()->getComm();
  const auto& offsets = layout.rank_offsets;
  const auto rank_of = [&offsets](std::int64_t unknown) {
    return static_cast<int>(std::upper_bound(offsets.begin(), offsets.end(), unknown) - offsets.begin()) - 1;
  };
  // The blocks of each rank in node order (-1: the masters' block, on the rank owning the masters).
  std::vector<std::vector<std::int64_t>> blocks(offsets.size() - 1);
  for (std::int64_t n = 0; n < space.node_count(); ++n)
    for (int i = 0; i < 3; ++i)
      if (layout.node_dofs[n][i] >= 0) {
        blocks[rank_of(layout.node_dofs[n][i])].push_back(n);
        break;
      }
  blocks[rank_of(layout.masters[0])].push_back(-1);

  mesh::Point centre{0.0, 0.0, 0.0};
  for (const auto& point : coordinates)
    for (int i = 0; i < 3; ++i) centre[i] += point[i] / static_cast<double>(coordinates.size());

  NodeBlocks result;
  result.row_of_unknown.assign(layout.count(), -1);
  std::vector<GlobalOrdinal> owned_rows;
  std::vector<std::int64_t> owned_blocks;
  GlobalOrdinal next = 0;
  const int rank = comm->getRank();
  for (std::size_t r = 0; r < blocks.size(); ++r)
    for (const auto node : blocks[r]) {
      if (node < 0) result.master_block = next;
      if (static_cast<int>(r) == rank) owned_blocks.push_back(node);
      for (int i = 0; i < 3; ++i, ++next) {
        const auto unknown = node < 0 ? layout.masters[i] : layout.node_dofs[node][i];
        if (unknown >= 0) result.row_of_unknown[unknown] = next;
        if (static_cast<int>(r) == rank) owned_rows.push_back(next);
      }
    }
  result.map = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                    Teuchos::ArrayView<const GlobalOrdinal>(owned_rows), 0, comm));
  result.rigid_body_modes = Teuchos::rcp(new MultiVector(result.map, 6));   // zero-initialized
  for (std::size_t b = 0; b < owned_blocks.size(); ++b) {
    const auto node = owned_blocks[b];
    if (node < 0) continue;
    const double x = coordinates[node][0] - centre[0], y = coordinates[node][1] - centre[1],
                 z = coordinates[node][2] - centre[2];
    // Column j's value at component i: translations e_i, rotations (e_a x r)_i about the axes a = X, Y, Z.
    const double motion[3][6] = {{1, 0, 0, 0, z, -y}, {0, 1, 0, -z, 0, x}, {0, 0, 1, y, -x, 0}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 6; ++j)
        result.rigid_body_modes->replaceLocalValue(static_cast<LocalOrdinal>(3 * b + i), j, motion[i][j]);
  }
  return result;
}

}  // namespace spatula::solvers
