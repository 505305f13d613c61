#include "discretization/dof_layout.hpp"

namespace spatula::discretization {

Constraints spatula_constraints(const mesh::HexMesh& mesh, const std::array<double, 3>& face_centre,
                                bool hold_contact_surface)
{
  Constraints constraints;
  constraints.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
  if (hold_contact_surface) constraints.fixed.push_back({mesh.nodes(mesh::Boundary::contact), 2});
  constraints.rigid_nodes = mesh.nodes(mesh::Boundary::end_face);
  constraints.rigid_centre = face_centre;
  return constraints;
}

DofLayout make_dof_layout(const NodeSpace& space, const Constraints& constraints, int ranks)
{
  DofLayout layout;
  const auto nodes = static_cast<std::size_t>(space.node_count());
  layout.rigid.assign(nodes, 0);
  for (auto n : constraints.rigid_nodes) layout.rigid[n] = 1;
  std::vector<std::array<char, 3>> held(nodes, {0, 0, 0});
  for (const auto& fixed : constraints.fixed)
    for (auto n : fixed.nodes) held[n][fixed.component] = 1;
  for (auto n = static_cast<std::size_t>(space.mesh_nodes); n < nodes; ++n)
    for (int i = 0; i < 3; ++i) {
      bool all = true;
      for (auto corner : space.corners[n])
        if (corner >= 0) all = all && held[corner][i];
      held[n][i] = all;
    }

  layout.node_dofs.assign(nodes, {DofLayout::fixed, DofLayout::fixed, DofLayout::fixed});
  std::int64_t next = 0;
  layout.rank_offsets.push_back(0);
  for (int rank = 0; rank < ranks; ++rank) {
    for (std::size_t n = 0; n < nodes; ++n) {
      if (space.owner[n] != rank || layout.rigid[n] || space.dependent[n]) continue;
      for (int i = 0; i < 3; ++i)
        if (!held[n][i]) layout.node_dofs[n][i] = next++;
    }
    if (rank == 0) {
      layout.masters = {next, next + 1, next + 2};
      next += 3;
    }
    layout.rank_offsets.push_back(next);
  }
  return layout;
}

}  // namespace spatula::discretization
