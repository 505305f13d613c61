#include "discretization/system_fields.hpp"

#include "discretization/system_topology.hpp"
#include "elements/solid_element.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace spatula::discretization {

void set_displacements(const DiscreteSystem& system, Vector& x, const std::vector<double>& u)
{
  const auto& impl = system.topology();
  const auto map = x.getMap();
  auto values = x.getDataNonConst(0);
  for (std::int64_t n = 0; n < impl.space.node_count(); ++n) {
    double value[3] = {0, 0, 0};
    if (n < impl.space.mesh_nodes) {
      for (int i = 0; i < 3; ++i) value[i] = u[3 * n + i];
    } else {   // an enrichment node: the mean of its corners (the field stays the mesh's)
      int corners = 0;
      for (auto c : impl.space.corners[n])
        if (c >= 0) {
          ++corners;
          for (int i = 0; i < 3; ++i) value[i] += u[3 * c + i];
        }
      for (int i = 0; i < 3; ++i) value[i] /= corners;
    }
    for (int i = 0; i < 3; ++i) {
      const auto id = impl.layout.node_dofs[n][i];
      if (id >= 0 && map->isNodeGlobalElement(id)) values[map->getLocalElement(id)] = value[i];
    }
  }
}

namespace {

// Displacements of every node of the space (N x 3), complete on every rank.
std::vector<double> all_displacements(const DiscreteSystem& system, const Vector& x, const NodeSpace& space,
                                        const DofLayout& layout, const std::array<double, 3>& centre,
                                        const RigidFaceDirections& directions, const Teuchos::Comm<int>& comm)
{
  double masters[master_count];
  for (int m = 0; m < master_count; ++m) masters[m] = system.master(x, Master(m));
  const int rank = comm.getRank();
  const auto map = x.getMap();
  const auto values = x.getData(0);
  std::vector<double> local(3 * space.node_count(), 0.0), global(local.size(), 0.0);
  for (std::int64_t n = 0; n < space.node_count(); ++n) {
    if (layout.rigid[n]) {
      if (rank != 0) continue;
      double d[3];
      for (int i = 0; i < 3; ++i) d[i] = space.coordinates[n][i] - centre[i];
      const auto motion = rigid_face_motion(masters, d, directions);
      for (int i = 0; i < 3; ++i) local[3 * n + i] = motion.u[i];
      continue;
    }
    for (int i = 0; i < 3; ++i) {   // each free component is written by its owner only
      const auto id = layout.node_dofs[n][i];
      if (id >= 0 && map->isNodeGlobalElement(id)) local[3 * n + i] = values[map->getLocalElement(id)];
    }
  }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), global.data());
  for (std::int64_t n = space.mesh_nodes; n < space.node_count(); ++n)
    if (space.dependent[n])
      for (int i = 0; i < 3; ++i)
        global[3 * n + i] = 0.5 * (global[3 * space.corners[n][0] + i] + global[3 * space.corners[n][1] + i]);
  return global;
}

}  // namespace

std::vector<double> node_displacements(const DiscreteSystem& system, const Vector& x)
{
  const auto& impl = system.topology();
  auto all = space_displacements(system, x);
  all.resize(3 * impl.space.mesh_nodes);
  return all;
}

std::vector<double> space_displacements(const DiscreteSystem& system, const Vector& x)
{
  const auto& impl = system.topology();
  return all_displacements(system, x, impl.space, impl.layout, impl.face_centre, impl.directions, *impl.comm);
}

void set_space_displacements(const DiscreteSystem& system, Vector& x, const std::vector<double>& u)
{
  const auto& impl = system.topology();
  if (u.size() != 3 * static_cast<std::size_t>(impl.space.node_count()))
    throw std::runtime_error("displacements for " + std::to_string(u.size() / 3) + " nodes given, the system has " +
                             std::to_string(impl.space.node_count()));
  const auto map = x.getMap();
  auto values = x.getDataNonConst(0);
  for (std::int64_t n = 0; n < impl.space.node_count(); ++n)
    for (int i = 0; i < 3; ++i) {
      const auto id = impl.layout.node_dofs[n][i];
      if (id >= 0 && map->isNodeGlobalElement(id)) values[map->getLocalElement(id)] = u[3 * n + i];
    }
}

std::vector<double> element_cauchy_trace(const DiscreteSystem& system, const Vector& x)
{
  const auto& impl = system.topology();
  const auto& solid = system.solid();
  const auto u = space_displacements(system, x);
  const auto law = laws::NeoHookean::from_young(solid.young, solid.poisson);
  std::vector<double> local(impl.mesh.element_count(), 0.0), global(local.size(), 0.0);
  auto trace = [&](const auto& nodes, auto shape, int order) {
    using Shape = decltype(shape);
    double X[Shape::nodes][3], ue[Shape::nodes][3];
    for (int a = 0; a < Shape::nodes; ++a)
      for (int i = 0; i < 3; ++i) {
        X[a][i] = impl.space.coordinates[nodes[a]][i];
        ue[a][i] = u[3 * nodes[a] + i];
      }
    return elements::mean_cauchy_trace<Shape>(law, X, ue, order);
  };
  for (auto e : impl.hex8) local[e] = trace(impl.mesh.elements[e], elements::Hex8Shape{}, solid.quadrature_order);
  for (auto k : impl.hex13)
    local[impl.space.hex13_elements[k]] =
        trace(impl.space.hex13_nodes[k], elements::Hex13Shape{}, std::max(solid.quadrature_order, 3));
  Teuchos::reduceAll(*impl.comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), global.data());
  return global;
}

}  // namespace spatula::discretization
