#pragma once
// Everything that carries a displacement, and the element blocks that use it. Without enrichment (Q1C1) these are
// the mesh nodes and Hex8 elements, with the contact faces as bilinear quadrilaterals. With Q1C2 every element
// with a contact face becomes a Hex13 (its bottom face biquadratic): a node is added at the middle of each contact
// edge (shared by the faces beside it) and at the centre of each contact face. A mid-edge node on an edge that a
// plain Hex8 element also uses (the edges along the rim axis, shared with P_I) would break conformity: it becomes
// a dependent node, u = (u_a + u_b) / 2 of the edge's corners, so the edge stays straight there.
#include "mesh/hex_mesh.hpp"
#include "mesh/partition.hpp"

#include <array>
#include <string>
#include <vector>

namespace spatula::discretization {

enum class Enrichment { q1c1, q1c2 };
const std::vector<std::string>& enrichment_names();   // "Q1C1", "Q1C2": in the order of Enrichment

struct NodeSpace {
  std::int64_t mesh_nodes = 0;                           // ids below this are mesh nodes
  std::vector<mesh::Point> coordinates;                  // reference positions of all nodes
  // Enrichment nodes: the mesh nodes they sit between (2 for a mid-edge node, 4 for a face centre; -1 padded).
  std::vector<std::array<std::int64_t, 4>> corners;
  std::vector<char> dependent;                           // follows the mean of its two corners (no unknowns)
  std::vector<int> owner;                                // rank owning each node

  // Element blocks (node ids in this space) with the mesh element each came from.
  std::vector<std::int64_t> hex8_elements;
  std::vector<std::int64_t> hex13_elements;
  std::vector<std::array<std::int64_t, 13>> hex13_nodes;
  // Contact faces: 4 (Q1C1) or 9 (Q1C2, Quad9Surface order) node ids each, with their element.
  int face_nodes = 4;
  std::vector<std::int64_t> face_elements;
  std::vector<std::array<std::int64_t, 9>> faces;

  std::int64_t node_count() const { return static_cast<std::int64_t>(coordinates.size()); }
};

NodeSpace make_node_space(const mesh::HexMesh& mesh, const mesh::Partition& partition, Enrichment enrichment);

}  // namespace spatula::discretization
