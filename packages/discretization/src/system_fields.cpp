#include "discretization/system_fields.hpp"

#include "discretization/system_topology.hpp"
#include "elements/quadrilateral_shape.hpp"
#include "elements/solid_element.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spatula::discretization {

void set_displacements(const DiscreteSystem& system, Vector& x, const std::vector<double>& u)
{
  const auto& topology = system.topology();
  const auto map = x.getMap();
  auto values = x.getDataNonConst(0);
  for (std::int64_t n = 0; n < topology.space.node_count(); ++n) {
    double value[3] = {0, 0, 0};
    if (n < topology.space.mesh_nodes) {
      for (int i = 0; i < 3; ++i) value[i] = u[3 * n + i];
    } else {   // an enrichment node: the mean of its corners (the field stays the mesh's)
      int corners = 0;
      for (auto c : topology.space.corners[n])
        if (c >= 0) {
          ++corners;
          for (int i = 0; i < 3; ++i) value[i] += u[3 * c + i];
        }
      for (int i = 0; i < 3; ++i) value[i] /= corners;
    }
    for (int i = 0; i < 3; ++i) {
      const auto id = topology.layout.node_dofs[n][i];
      if (id >= 0 && map->isNodeGlobalElement(id)) values[map->getLocalElement(id)] = value[i];
    }
  }
}

std::vector<double> node_displacements(const DiscreteSystem& system, const Vector& x)
{
  auto all = space_displacements(system, x);
  all.resize(3 * system.topology().space.mesh_nodes);
  return all;
}

std::vector<double> space_displacements(const DiscreteSystem& system, const Vector& x)
{
  const auto& topology = system.topology();
  const auto& space = topology.space;
  const auto& layout = topology.layout;
  double masters[master_count];
  for (int m = 0; m < master_count; ++m) masters[m] = system.master(x, Master(m));
  const int rank = topology.comm->getRank();
  const auto map = x.getMap();
  const auto values = x.getData(0);
  std::vector<double> local(3 * space.node_count(), 0.0), global(local.size(), 0.0);
  for (std::int64_t n = 0; n < space.node_count(); ++n) {
    if (layout.rigid[n]) {
      if (rank != 0) continue;
      double d[3];
      for (int i = 0; i < 3; ++i) d[i] = space.coordinates[n][i] - topology.face_centre[i];
      const auto motion = rigid_face_motion(masters, d, topology.directions);
      for (int i = 0; i < 3; ++i) local[3 * n + i] = motion.u[i];
      continue;
    }
    for (int i = 0; i < 3; ++i) {   // each free component is written by its owner only
      const auto id = layout.node_dofs[n][i];
      if (id >= 0 && map->isNodeGlobalElement(id)) local[3 * n + i] = values[map->getLocalElement(id)];
    }
  }
  Teuchos::reduceAll(*topology.comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(),
                     global.data());
  for (std::int64_t n = space.mesh_nodes; n < space.node_count(); ++n)
    if (space.dependent[n])
      for (int i = 0; i < 3; ++i)
        global[3 * n + i] = 0.5 * (global[3 * space.corners[n][0] + i] + global[3 * space.corners[n][1] + i]);
  return global;
}

void set_space_displacements(const DiscreteSystem& system, Vector& x, const std::vector<double>& u)
{
  const auto& topology = system.topology();
  if (u.size() != 3 * static_cast<std::size_t>(topology.space.node_count()))
    throw std::runtime_error("displacements for " + std::to_string(u.size() / 3) + " nodes given, the system has " +
                             std::to_string(topology.space.node_count()));
  const auto map = x.getMap();
  auto values = x.getDataNonConst(0);
  for (std::int64_t n = 0; n < topology.space.node_count(); ++n)
    for (int i = 0; i < 3; ++i) {
      const auto id = topology.layout.node_dofs[n][i];
      if (id >= 0 && map->isNodeGlobalElement(id)) values[map->getLocalElement(id)] = u[3 * n + i];
    }
}

std::vector<double> element_cauchy_trace(const DiscreteSystem& system, const Vector& x)
{
  const auto& topology = system.topology();
  const auto u = space_displacements(system, x);
  const auto& model = system.solid_model();
  std::vector<double> local(topology.mesh.element_count(), 0.0), global(local.size(), 0.0);
  auto trace = [&](const auto& nodes, int count) {
    double X[13][3], ue[13][3];
    for (int a = 0; a < count; ++a)
      for (int i = 0; i < 3; ++i) {
        X[a][i] = topology.space.coordinates[nodes[a]][i];
        ue[a][i] = u[3 * nodes[a] + i];
      }
    return model.mean_cauchy_trace(X, ue, count);
  };
  for (auto e : topology.hex8) local[e] = trace(topology.mesh.elements[e], 8);
  for (auto k : topology.hex13) local[topology.space.hex13_elements[k]] = trace(topology.space.hex13_nodes[k], 13);
  Teuchos::reduceAll(*topology.comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), global.data());
  return global;
}

namespace {

// The mean over a contact face of a value given at its quadrature points (the contact kernel's: point (a, b) at
// a order + b), weighted by the undeformed area each point stands for, as the kernel integrates.
template <class Surface>
double face_mean(const NodeSpace& space, std::size_t face, int order, const double* values, int stride)
{
  double Xn[Surface::nodes][3];
  for (int k = 0; k < Surface::nodes; ++k)
    for (int i = 0; i < 3; ++i) Xn[k][i] = space.coordinates[space.faces[face][k]][i];
  double area = 0.0, sum = 0.0;
  for (int a = 0; a < order; ++a)
    for (int b = 0; b < order; ++b) {
      double s, t, ws, wt, shape[Surface::nodes], derivatives[Surface::nodes][2];
      elements::gauss_point(order, a, s, ws);
      elements::gauss_point(order, b, t, wt);
      Surface::evaluate(s, t, shape, derivatives);
      const double dA = elements::area_element<Surface>(derivatives, Xn) * ws * wt;
      area += dA;
      sum += dA * values[(a * order + b) * stride];
    }
  return sum / area;
}

}  // namespace

std::vector<double> element_contact_dissipation(const DiscreteSystem& system)
{
  const auto* law = system.contact_model();
  if (!law || law->dissipated_index() < 0) return {};
  const auto history = system.contact_history();
  const auto& space = system.nodes();
  const int order = law->quadrature_order(), size = law->history_size();
  std::vector<double> field(system.topology().mesh.element_count(), 0.0);
  for (std::size_t f = 0; f < space.faces.size(); ++f) {
    const double* values = history.data() + f * order * order * size + law->dissipated_index();
    field[space.face_elements[f]] = space.face_nodes == 9
                                        ? face_mean<elements::Quad9Surface>(space, f, order, values, size)
                                        : face_mean<elements::Quad4Surface>(space, f, order, values, size);
  }
  return field;
}

}  // namespace spatula::discretization
