#include "discretization/node_space.hpp"

#include "mesh/hexahedron.hpp"
#include "parameters/parameter_validation.hpp"

#include <algorithm>
#include <map>

namespace spatula::discretization {

const std::vector<std::string>& enrichment_names()
{
  static const std::vector<std::string> names = {"Q1C1", "Q1C2"};
  return names;
}

NodeSpace make_node_space(const mesh::HexMesh& mesh, const mesh::Partition& partition, Enrichment enrichment)
{
  NodeSpace space;
  space.mesh_nodes = mesh.node_count();
  space.coordinates = mesh.coordinates;
  space.corners.assign(mesh.coordinates.size(), {-1, -1, -1, -1});
  space.dependent.assign(mesh.coordinates.size(), 0);
  space.owner = partition.node_owner;

  std::vector<char> has_face(mesh.element_count(), 0);
  for (const auto& side : mesh.sides(mesh::Boundary::contact)) {
    if (side.face != 4) throw std::logic_error("contact faces must be element bottoms (local face 4)");
    has_face[side.element] = 1;
  }
  const bool enriched = enrichment == Enrichment::q1c2;
  space.face_nodes = enriched ? 9 : 4;
  for (std::int64_t e = 0; e < mesh.element_count(); ++e)
    if (!(enriched && has_face[e])) space.hex8_elements.push_back(e);
  if (!enriched) {
    for (const auto& side : mesh.sides(mesh::Boundary::contact)) {
      const auto& element = mesh.elements[side.element];
      space.face_elements.push_back(side.element);
      space.faces.push_back({element[0], element[1], element[2], element[3], -1, -1, -1, -1, -1});
    }
    return space;
  }

  // Edges used by plain Hex8 elements: a mid-edge node there must follow the edge.
  auto key = [](std::int64_t a, std::int64_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  std::map<std::pair<std::int64_t, std::int64_t>, char> plain_edges;
  constexpr int hex_edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                    {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (auto e : space.hex8_elements)
    for (const auto& edge : hex_edges) plain_edges[key(mesh.elements[e][edge[0]], mesh.elements[e][edge[1]])] = 1;

  std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> mid_edge;
  auto add_node = [&](const mesh::Point& x, std::array<std::int64_t, 4> corners, bool dependent, int owner) {
    space.coordinates.push_back(x);
    space.corners.push_back(corners);
    space.dependent.push_back(dependent);
    space.owner.push_back(owner);
    return space.node_count() - 1;
  };
  for (const auto& side : mesh.sides(mesh::Boundary::contact)) {
    const auto e = side.element;
    const auto& element = mesh.elements[e];
    const int owner = partition.element_owner[e];
    std::array<std::int64_t, 13> nodes{};
    for (int a = 0; a < 8; ++a) nodes[a] = element[a];
    mesh::Point centre{0, 0, 0};
    for (int k = 0; k < 4; ++k) {
      const auto a = element[k], b = element[(k + 1) % 4];
      const auto& xa = mesh.coordinates[a];
      const auto& xb = mesh.coordinates[b];
      for (int i = 0; i < 3; ++i) centre[i] += 0.25 * xa[i];
      auto [it, fresh] = mid_edge.try_emplace(key(a, b), -1);
      if (fresh) {
        it->second = add_node({0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1]), 0.5 * (xa[2] + xb[2])}, {a, b, -1, -1},
                              plain_edges.count(key(a, b)) > 0, owner);
      } else {
        space.owner[it->second] = std::min(space.owner[it->second], owner);
      }
      nodes[8 + k] = it->second;
    }
    nodes[12] = add_node(centre, {element[0], element[1], element[2], element[3]}, false, owner);
    space.hex13_elements.push_back(e);
    space.hex13_nodes.push_back(nodes);
    space.face_elements.push_back(e);
    space.faces.push_back({nodes[0], nodes[1], nodes[2], nodes[3], nodes[8], nodes[9], nodes[10], nodes[11], nodes[12]});
  }
  return space;
}

}  // namespace spatula::discretization
