#include "mesh/partition.hpp"

#include <algorithm>
#include <numeric>

namespace spatula::mesh {

namespace {

void bisect(std::vector<std::int64_t>::iterator begin, std::vector<std::int64_t>::iterator end, int first_rank,
            int ranks, const std::vector<Point>& centroids, std::vector<int>& owner)
{
  if (ranks == 1) {
    for (auto it = begin; it != end; ++it) owner[*it] = first_rank;
    return;
  }
  Point low = centroids[*begin], high = low;
  for (auto it = begin; it != end; ++it)
    for (int i = 0; i < 3; ++i) {
      low[i] = std::min(low[i], centroids[*it][i]);
      high[i] = std::max(high[i], centroids[*it][i]);
    }
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (high[i] - low[i] > high[axis] - low[axis]) axis = i;
  const int left_ranks = ranks / 2;
  const auto split = begin + (end - begin) * left_ranks / ranks;
  std::nth_element(begin, split, end, [&](std::int64_t a, std::int64_t b) {
    return centroids[a][axis] != centroids[b][axis] ? centroids[a][axis] < centroids[b][axis] : a < b;
  });
  bisect(begin, split, first_rank, left_ranks, centroids, owner);
  bisect(split, end, first_rank + left_ranks, ranks - left_ranks, centroids, owner);
}

}  // namespace

Partition partition_mesh(const HexMesh& mesh, int ranks)
{
  Partition partition;
  partition.ranks = ranks;
  std::vector<Point> centroids(mesh.elements.size());
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    Point c{0, 0, 0};
    for (auto n : mesh.elements[e])
      for (int i = 0; i < 3; ++i) c[i] += mesh.coordinates[n][i] / 8.0;
    centroids[e] = c;
  }
  std::vector<std::int64_t> order(mesh.elements.size());
  std::iota(order.begin(), order.end(), 0);
  partition.element_owner.assign(mesh.elements.size(), 0);
  bisect(order.begin(), order.end(), 0, ranks, centroids, partition.element_owner);

  partition.node_owner.assign(mesh.coordinates.size(), ranks);
  for (std::size_t e = 0; e < mesh.elements.size(); ++e)
    for (auto n : mesh.elements[e]) partition.node_owner[n] = std::min(partition.node_owner[n], partition.element_owner[e]);
  return partition;
}

std::vector<std::int64_t> Partition::elements_of(int rank) const
{
  std::vector<std::int64_t> elements;
  for (std::size_t e = 0; e < element_owner.size(); ++e)
    if (element_owner[e] == rank) elements.push_back(static_cast<std::int64_t>(e));
  return elements;
}

std::vector<std::int64_t> Partition::owned_nodes_of(int rank) const
{
  std::vector<std::int64_t> nodes;
  for (std::size_t n = 0; n < node_owner.size(); ++n)
    if (node_owner[n] == rank) nodes.push_back(static_cast<std::int64_t>(n));
  return nodes;
}

std::vector<std::int64_t> Partition::shared_nodes_of(int rank, const HexMesh& mesh) const
{
  std::vector<std::int64_t> nodes;
  for (std::size_t e = 0; e < element_owner.size(); ++e)
    if (element_owner[e] == rank)
      for (auto n : mesh.elements[e])
        if (node_owner[n] != rank) nodes.push_back(n);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace spatula::mesh
