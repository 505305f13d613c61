#include "discrete_system.hpp"

#include "element_scatter.hpp"
#include "parameter_validation.hpp"
#include "solid_hex8.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Assembly_Helpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <map>

namespace spatula::discretization {

void SolidParameters::declare(Teuchos::ParameterList& material)
{
  using parameters::Range;
  parameters::declare_double(material, "E", 2.0, "Young's modulus [GPa]", Range::positive());
  parameters::declare_double(material, "nu", 0.2, "Poisson's ratio", {-1.0, 0.5, true, true});
  parameters::declare_int(material, "quadrature order", 2, "Gauss points per direction in each hexahedron",
                          Range::closed(1, 4));
}

SolidParameters SolidParameters::from(const Teuchos::ParameterList& material)
{
  SolidParameters p;
  p.young = material.get<double>("E");
  p.poisson = material.get<double>("nu");
  p.quadrature_order = material.get<int>("quadrature order");
  return p;
}

namespace {

template <class T>
using DeviceView = Kokkos::View<T, device_type>;

// Bulk solid: one Hex8 kernel per local element; reduces the energy, reports an inverted element.
struct SolidKernel {
  ElementScatter scatter;
  DeviceView<const int* [8]> element_nodes;
  DeviceView<const std::int64_t*> element_ids;
  DeviceView<const double* [3]> coordinates;
  DeviceView<std::int64_t[1]> inverted;   // global id + 1 of an inverted element, 0 if none
  laws::NeoHookean law;
  int order = 2;

  KOKKOS_INLINE_FUNCTION void operator()(const int element, double& energy) const
  {
    int nodes[8];
    double X[8][3], u[8][3];
    for (int a = 0; a < 8; ++a) {
      nodes[a] = element_nodes(element, a);
      for (int i = 0; i < 3; ++i) X[a][i] = coordinates(nodes[a], i);
      scatter.displacement(nodes[a], u[a]);
    }
    double element_energy, r[24], K[24][24];
    const auto status = elements::hex8_solid(law, X, u, order, element_energy, r, scatter.with_matrix ? K : nullptr);
    if (status != elements::ElementStatus::ok) {
      Kokkos::atomic_fetch_max(&inverted(0), element_ids(element) + 1);
      return;
    }
    energy += element_energy;
    scatter.add<8>(nodes, r, K);
  }
};

}  // namespace

struct DiscreteSystem::Implementation {
  Teuchos::RCP<const Teuchos::Comm<int>> comm;
  const mesh::HexMesh& mesh;
  DofLayout layout;
  SolidParameters solid;
  MasterControl control;
  std::array<double, 3> face_centre{};

  std::vector<std::int64_t> elements;         // this rank's elements (global ids)
  std::vector<std::int64_t> local_nodes;      // nodes touched by them
  Teuchos::RCP<const Map> owned, overlap;     // unknowns: owned, and owned + shared (owned first)
  Teuchos::RCP<const Import> importer;
  Teuchos::RCP<FECrsGraph> graph;
  Teuchos::RCP<FECrsMatrix> matrix;
  Teuchos::RCP<FEMultiVector> residual;
  Teuchos::RCP<Vector> state;                 // on the overlap map
  std::array<int, master_count> master_unknown{-1, -1};

  DeviceView<int* [8]> element_nodes;
  DeviceView<std::int64_t*> element_ids;
  DeviceView<double* [3]> coordinates;
  DeviceView<int* [3]> node_unknown;
  DeviceView<double* [3]> node_offset;
  DeviceView<int*> column_of;

  Implementation(const mesh::HexMesh& mesh_, const mesh::Partition& partition, const Constraints& constraints,
                 const SolidParameters& solid_, Teuchos::RCP<const Teuchos::Comm<int>> comm_)
      : comm(std::move(comm_)), mesh(mesh_), layout(make_dof_layout(mesh_, partition, constraints)), solid(solid_),
        face_centre(constraints.rigid_centre)
  {
    const int rank = comm->getRank();
    elements = partition.elements_of(rank);
    std::vector<int> local_of(mesh.node_count(), -1);
    for (auto e : elements)
      for (auto n : mesh.elements[e])
        if (local_of[n] < 0) {
          local_of[n] = static_cast<int>(local_nodes.size());
          local_nodes.push_back(n);
        }

    // Unknowns: owned block, then the shared ones this rank's elements touch.
    std::vector<GlobalOrdinal> owned_ids, shared_ids;
    for (auto id = layout.rank_offsets[rank]; id < layout.rank_offsets[rank + 1]; ++id) owned_ids.push_back(id);
    auto is_owned = [&](std::int64_t id) { return id >= layout.rank_offsets[rank] && id < layout.rank_offsets[rank + 1]; };
    bool touches_face = false;
    for (auto n : local_nodes) {
      touches_face |= layout.rigid[n] != 0;
      for (auto id : layout.node_dofs[n])
        if (id >= 0 && !is_owned(id)) shared_ids.push_back(id);
    }
    if (touches_face)
      for (auto id : layout.masters)
        if (!is_owned(id)) shared_ids.push_back(id);
    std::sort(shared_ids.begin(), shared_ids.end());
    shared_ids.erase(std::unique(shared_ids.begin(), shared_ids.end()), shared_ids.end());
    std::vector<GlobalOrdinal> overlap_ids = owned_ids;
    overlap_ids.insert(overlap_ids.end(), shared_ids.begin(), shared_ids.end());
    const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
    owned = Teuchos::rcp(new Map(invalid, owned_ids.data(), owned_ids.size(), 0, comm));
    overlap = Teuchos::rcp(new Map(invalid, overlap_ids.data(), overlap_ids.size(), 0, comm));
    importer = Teuchos::rcp(new Import(owned, overlap));
    for (int m = 0; m < master_count; ++m) master_unknown[m] = overlap->getLocalElement(layout.masters[m]);
    if (touches_face && (master_unknown[0] < 0 || master_unknown[1] < 0))
      throw std::logic_error("end-face masters missing from the overlap map");

    build_views(local_of);
    build_graph();
    matrix = Teuchos::rcp(new FECrsMatrix(graph));
    residual = Teuchos::rcp(new FEMultiVector(owned, graph->getImporter(), 1));
    state = Teuchos::rcp(new Vector(overlap));
    // Local column of every overlap unknown (the element kernels address matrix entries by local column).
    auto columns = Kokkos::create_mirror_view(column_of);
    const auto column_map = matrix->getColMap();
    for (std::size_t lid = 0; lid < overlap_ids.size(); ++lid)
      columns(lid) = column_map->getLocalElement(overlap_ids[lid]);
    Kokkos::deep_copy(column_of, columns);
  }

  void build_views(const std::vector<int>& local_of)
  {
    element_nodes = DeviceView<int* [8]>("element nodes", elements.size());
    element_ids = DeviceView<std::int64_t*>("element ids", elements.size());
    coordinates = DeviceView<double* [3]>("node coordinates", local_nodes.size());
    node_unknown = DeviceView<int* [3]>("node unknowns", local_nodes.size());
    node_offset = DeviceView<double* [3]>("rigid offsets", local_nodes.size());
    column_of = DeviceView<int*>("column of unknown", overlap->getNodeNumElements());
    auto h_elements = Kokkos::create_mirror_view(element_nodes);
    auto h_ids = Kokkos::create_mirror_view(element_ids);
    auto h_coordinates = Kokkos::create_mirror_view(coordinates);
    auto h_unknown = Kokkos::create_mirror_view(node_unknown);
    auto h_offset = Kokkos::create_mirror_view(node_offset);
    for (std::size_t e = 0; e < elements.size(); ++e) {
      h_ids(e) = elements[e];
      for (int a = 0; a < 8; ++a) h_elements(e, a) = local_of[mesh.elements[elements[e]][a]];
    }
    for (std::size_t n = 0; n < local_nodes.size(); ++n) {
      const auto node = local_nodes[n];
      for (int i = 0; i < 3; ++i) {
        h_coordinates(n, i) = mesh.coordinates[node][i];
        h_offset(n, i) = mesh.coordinates[node][i] - face_centre[i];
        const auto id = layout.node_dofs[node][i];
        h_unknown(n, i) = layout.rigid[node] ? rigid_component
                          : id < 0           ? fixed_component
                                             : overlap->getLocalElement(id);
      }
    }
    Kokkos::deep_copy(element_nodes, h_elements);
    Kokkos::deep_copy(element_ids, h_ids);
    Kokkos::deep_copy(coordinates, h_coordinates);
    Kokkos::deep_copy(node_unknown, h_unknown);
    Kokkos::deep_copy(node_offset, h_offset);
  }

  // The unknowns an element couples: its free components and, if it touches the end face, both masters.
  std::vector<GlobalOrdinal> element_unknowns(std::int64_t e) const
  {
    std::vector<GlobalOrdinal> ids;
    bool rigid = false;
    for (auto n : mesh.elements[e]) {
      rigid |= layout.rigid[n] != 0;
      for (auto id : layout.node_dofs[n])
        if (id >= 0) ids.push_back(id);
    }
    if (rigid) ids.insert(ids.end(), layout.masters.begin(), layout.masters.end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
  }

  void build_graph()
  {
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: graph"));
    std::vector<std::vector<GlobalOrdinal>> rows(overlap->getNodeNumElements());
    for (auto e : elements) {
      const auto ids = element_unknowns(e);
      for (auto row : ids) {
        auto& entries = rows[overlap->getLocalElement(row)];
        entries.insert(entries.end(), ids.begin(), ids.end());
      }
    }
    Kokkos::DualView<std::size_t*, device_type> counts("row counts", rows.size());
    for (std::size_t lid = 0; lid < rows.size(); ++lid) {
      auto& entries = rows[lid];
      entries.push_back(overlap->getGlobalElement(lid));   // every row has its diagonal (prescribed masters)
      std::sort(entries.begin(), entries.end());
      entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
      counts.h_view(lid) = entries.size();
    }
    counts.modify_host();
    counts.sync_device();
    graph = Teuchos::rcp(new FECrsGraph(owned, overlap, counts));
    Tpetra::beginAssembly(*graph);
    for (std::size_t lid = 0; lid < rows.size(); ++lid)
      graph->insertGlobalIndices(overlap->getGlobalElement(lid), rows[lid].size(), rows[lid].data());
    Tpetra::endAssembly(*graph);
  }

  ElementScatter make_scatter(double alpha, double lift, bool with_residual, bool with_matrix)
  {
    ElementScatter scatter;
    scatter.column_of = column_of;
    scatter.node_unknown = node_unknown;
    scatter.node_offset = node_offset;
    for (int m = 0; m < master_count; ++m) {
      scatter.master_unknown[m] = master_unknown[m];
      scatter.master_prescribed[m] = control.prescribed[m];
    }
    scatter.alpha = alpha;
    scatter.lift = lift;
    scatter.with_residual = with_residual;
    scatter.with_matrix = with_matrix;
    scatter.state = state->getLocalViewDevice(Tpetra::Access::ReadOnly);
    if (with_residual) scatter.residual = residual->getLocalViewDevice(Tpetra::Access::ReadWrite);
    if (with_matrix) scatter.matrix = matrix->getLocalMatrixDevice();
    return scatter;
  }

  double master_value(const Vector& x, Master which) const
  {
    const auto id = layout.masters[static_cast<int>(which)];
    double value = 0.0;
    const int owner = 0;
    if (comm->getRank() == owner) value = x.getData()[x.getMap()->getLocalElement(id)];
    Teuchos::broadcast(*comm, owner, Teuchos::outArg(value));
    return value;
  }

  Evaluation evaluate(const Vector& x, Vector* out_residual, bool with_jacobian)
  {
    Evaluation result;
    state->doImport(x, *importer, Tpetra::INSERT);
    const double alpha = master_value(x, Master::rotation), lift = master_value(x, Master::lift);
    const bool with_residual = true;   // always: the reactions and the energy come with it
    Tpetra::beginAssembly(*residual);
    residual->putScalar(0.0);
    if (with_jacobian) {
      Tpetra::beginAssembly(*matrix);
      matrix->setAllToScalar(0.0);
    }
    DeviceView<std::int64_t[1]> inverted("inverted element");
    double energy = 0.0;
    {
      Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer(with_jacobian ? "spatula: assembly bulk (residual + tangent)"
                                                                                  : "spatula: assembly bulk (residual)"));
      SolidKernel kernel{make_scatter(alpha, lift, with_residual, with_jacobian), element_nodes, element_ids,
                         coordinates, inverted,
                         laws::NeoHookean::from_young(solid.young, solid.poisson), solid.quadrature_order};
      Kokkos::parallel_reduce("spatula: solid hex8 assembly",
                              Kokkos::RangePolicy<execution_space>(0, static_cast<int>(elements.size())), kernel,
                              energy);
      // Identity rows of prescribed masters (their owner adds the diagonal once).
      if (with_jacobian) {
        auto local = matrix->getLocalMatrixDevice();
        const auto columns = column_of;
        for (int m = 0; m < master_count; ++m) {
          const int unknown = owned->getLocalElement(layout.masters[m]);
          if (!control.prescribed[m] || unknown < 0) continue;
          Kokkos::parallel_for("spatula: prescribed master diagonal", Kokkos::RangePolicy<execution_space>(0, 1),
                               KOKKOS_LAMBDA(int) {
                                 const int column = columns(unknown);
                                 const double one = 1.0;
                                 local.sumIntoValues(unknown, &column, 1, &one, false, true);
                               });
        }
      }
      Kokkos::fence();
    }
    {
      Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: assembly communication"));
      Tpetra::endAssembly(*residual);
      if (with_jacobian) Tpetra::endAssembly(*matrix);
    }
    auto h_inverted = Kokkos::create_mirror_view(inverted);
    Kokkos::deep_copy(h_inverted, inverted);
    std::int64_t bad = h_inverted(0);
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, bad, Teuchos::outArg(bad));
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, energy, Teuchos::outArg(result.internal_energy));
    result.admissible = bad == 0;
    result.inverted_element = bad - 1;

    // Reactions: the master rows' internal forces, then prescribed rows become identity rows (residual 0).
    auto values = residual->getDataNonConst(0);
    for (int m = 0; m < master_count; ++m) {
      const int unknown = owned->getLocalElement(layout.masters[m]);
      double reaction = unknown >= 0 ? values[unknown] : 0.0;
      Teuchos::broadcast(*comm, 0, Teuchos::outArg(reaction));
      result.master_residual[m] = reaction;
      if (unknown >= 0 && control.prescribed[m]) values[unknown] = 0.0;
    }
    values = Teuchos::null;
    if (out_residual) out_residual->assign(*residual);
    return result;
  }
};

DiscreteSystem::DiscreteSystem(const mesh::HexMesh& mesh, const mesh::Partition& partition,
                               const Constraints& constraints, const SolidParameters& solid,
                               Teuchos::RCP<const Teuchos::Comm<int>> comm)
    : implementation_(std::make_unique<Implementation>(mesh, partition, constraints, solid, std::move(comm)))
{
}

DiscreteSystem::~DiscreteSystem() = default;

Teuchos::RCP<const Map> DiscreteSystem::owned_map() const { return implementation_->owned; }
Teuchos::RCP<Vector> DiscreteSystem::create_vector() const { return Teuchos::rcp(new Vector(implementation_->owned)); }
Teuchos::RCP<CrsMatrix> DiscreteSystem::jacobian() const { return implementation_->matrix; }
const DofLayout& DiscreteSystem::layout() const { return implementation_->layout; }
void DiscreteSystem::set_control(const MasterControl& control) { implementation_->control = control; }
const MasterControl& DiscreteSystem::control() const { return implementation_->control; }

double DiscreteSystem::master(const Vector& x, Master which) const { return implementation_->master_value(x, which); }

void DiscreteSystem::set_master(Vector& x, Master which, double value) const
{
  const auto id = implementation_->layout.masters[static_cast<int>(which)];
  if (x.getMap()->isNodeGlobalElement(id)) x.replaceGlobalValue(id, value);
}

Evaluation DiscreteSystem::evaluate(const Vector& x, Vector* residual, bool with_jacobian)
{
  return implementation_->evaluate(x, residual, with_jacobian);
}

void DiscreteSystem::set_displacements(Vector& x, const std::vector<double>& u) const
{
  const auto& layout = implementation_->layout;
  const auto map = x.getMap();
  auto values = x.getDataNonConst(0);
  for (std::size_t n = 0; n < layout.node_dofs.size(); ++n)
    for (int i = 0; i < 3; ++i) {
      const auto id = layout.node_dofs[n][i];
      if (id >= 0 && map->isNodeGlobalElement(id)) values[map->getLocalElement(id)] = u[3 * n + i];
    }
}

std::vector<double> DiscreteSystem::node_displacements(const Vector& x) const
{
  auto& impl = *implementation_;
  impl.state->doImport(x, *impl.importer, Tpetra::INSERT);
  const double alpha = master(x, Master::rotation), lift = master(x, Master::lift);
  const auto values = impl.state->getData(0);
  std::vector<double> local(3 * impl.mesh.node_count(), 0.0), global(local.size(), 0.0);
  const int rank = impl.comm->getRank();
  for (std::int64_t n = 0; n < impl.mesh.node_count(); ++n) {
    bool mine = false;   // owned nodes: every node is written by exactly one rank
    for (auto id : impl.layout.node_dofs[n]) mine |= id >= impl.layout.rank_offsets[rank] && id < impl.layout.rank_offsets[rank + 1];
    if (impl.layout.rigid[n]) {
      if (rank != 0) continue;
      double d[3];
      for (int i = 0; i < 3; ++i) d[i] = impl.mesh.coordinates[n][i] - impl.face_centre[i];
      const auto motion = rigid_face_motion(alpha, lift, d);
      for (int i = 0; i < 3; ++i) local[3 * n + i] = motion.u[i];
      continue;
    }
    if (!mine) continue;
    for (int i = 0; i < 3; ++i) {
      const auto id = impl.layout.node_dofs[n][i];
      if (id >= 0) local[3 * n + i] = values[impl.overlap->getLocalElement(id)];
    }
  }
  Teuchos::reduceAll(*impl.comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), global.data());
  return global;
}

std::vector<double> DiscreteSystem::element_cauchy_trace(const Vector& x) const
{
  auto& impl = *implementation_;
  const auto u = node_displacements(x);
  const auto law = laws::NeoHookean::from_young(impl.solid.young, impl.solid.poisson);
  std::vector<double> local(impl.mesh.element_count(), 0.0), global(local.size(), 0.0);
  for (auto e : impl.elements) {
    double X[8][3], ue[8][3];
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i) {
        X[a][i] = impl.mesh.coordinates[impl.mesh.elements[e][a]][i];
        ue[a][i] = u[3 * impl.mesh.elements[e][a] + i];
      }
    local[e] = elements::hex8_mean_cauchy_trace(law, X, ue, impl.solid.quadrature_order);
  }
  Teuchos::reduceAll(*impl.comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), global.data());
  return global;
}

}  // namespace spatula::discretization
