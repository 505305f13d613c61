#pragma once
// Global numbering of the unknowns, identical on every rank: the free displacement components of the nodes
// owned by rank 0, then the three master unknowns of the rigid end face (rotation, lift, slide), then the free components
// of rank 1's nodes, and so on; each rank's block is contiguous (as MUMPS' distributed input wants).
// Not unknowns: the fixed components listed in the constraints (u_y on the symmetry plane, ...), every component
// of a rigid end-face node (it follows the masters, see rigid_face.hpp), and dependent enrichment nodes.
#include "discretization/node_space.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace spatula::discretization {

// What is held: components fixed at zero (of mesh nodes; an enrichment node is held where all its corners are),
// and the mesh nodes moving with the rigid end face about `rigid_centre`.
struct Constraints {
  struct Fixed {
    std::vector<std::int64_t> nodes;
    int component = 0;
  };
  std::vector<Fixed> fixed;
  std::vector<std::int64_t> rigid_nodes;
  std::array<double, 3> rigid_centre{};
  std::array<double, 3> lift_direction{0.0, 0.0, 1.0};    // d: unit, in the X-Z plane
  std::array<double, 3> slide_direction{1.0, 0.0, 0.0};   // e: unit, in the X-Z plane
};

// The spatula's constraints: u_y = 0 on the symmetry plane, the end face rigid about P1 (lifted along Z), and
// optionally the pad's contact surface held at Z = 0 (a check without adhesion).
Constraints spatula_constraints(const mesh::HexMesh& mesh, const std::array<double, 3>& face_centre,
                                bool hold_contact_surface);

struct DofLayout {
  static constexpr std::int64_t fixed = -1;

  std::vector<std::array<std::int64_t, 3>> node_dofs;   // per node of the NodeSpace: global id or `fixed`
  std::vector<char> rigid;                              // node follows the end face
  std::array<std::int64_t, 3> masters{};                 // global ids of rotation, lift, slide
  std::vector<std::int64_t> rank_offsets;               // rank r owns [offsets[r], offsets[r+1])
  std::int64_t count() const { return rank_offsets.back(); }
};

DofLayout make_dof_layout(const NodeSpace& space, const Constraints& constraints, int ranks);

}  // namespace spatula::discretization
