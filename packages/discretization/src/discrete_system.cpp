#include "discretization/discrete_system.hpp"

#include "parameters/parameter_validation.hpp"
#include "discretization/solid_kernel.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Assembly_Helpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

namespace spatula::discretization {

void SolidParameters::declare(Teuchos::ParameterList& material)
{
  const SolidParameters d;   // the defaults
  using parameters::Range;
  parameters::declare_double(material, "E", d.young, "Young's modulus [GPa]", Range::positive());
  parameters::declare_double(material, "nu", d.poisson, "Poisson's ratio", {-1.0, 0.5, true, true});
  parameters::declare_int(material, "quadrature order", d.quadrature_order,
                          "Gauss points per direction in each hexahedron",
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

// Adds `value` to the diagonal of each row in the range but the `skip`ped ones (prescribed masters): the proximal
// damping and the identity rows of prescribed masters. A named functor, not a lambda: CUDA cannot compile a device
// lambda inside the private DiscreteSystem::Implementation.
struct AddToDiagonal {
  CrsMatrix::local_matrix_device_type matrix;
  Kokkos::View<const int*, device_type> column_of;
  double value;
  int skip[master_count];

  KOKKOS_INLINE_FUNCTION void operator()(const int row) const
  {
    for (int m = 0; m < master_count; ++m)
      if (row == skip[m]) return;
    const int column = column_of(row);
    matrix.sumIntoValues(row, &column, 1, &value, false, true);
  }
};

// Undeformed area of a contact face (its corners span the bilinear reference face).
double face_area(const NodeSpace& space, const std::array<std::int64_t, 9>& face)
{
  double area = 0.0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      double s, t, ws, wt, N[4], dN[4][2];
      elements::gauss_point(2, a, s, ws);
      elements::gauss_point(2, b, t, wt);
      elements::Quad4Surface::evaluate(s, t, N, dN);
      double Xs[3] = {0, 0, 0}, Xt[3] = {0, 0, 0};
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 3; ++i) {
          Xs[i] += dN[k][0] * space.coordinates[face[k]][i];
          Xt[i] += dN[k][1] * space.coordinates[face[k]][i];
        }
      area += std::hypot(Xs[1] * Xt[2] - Xs[2] * Xt[1], Xs[2] * Xt[0] - Xs[0] * Xt[2], Xs[0] * Xt[1] - Xs[1] * Xt[0]) *
              ws * wt;
    }
  return area;
}

template <class T>
DeviceView<T*> to_device(const std::string& label, const std::vector<T>& values)
{
  DeviceView<T*> view(label, values.size());
  auto host = Kokkos::create_mirror_view(view);
  for (std::size_t i = 0; i < values.size(); ++i) host(i) = values[i];
  Kokkos::deep_copy(view, host);
  return view;
}

}  // namespace

struct DiscreteSystem::Implementation {
  Teuchos::RCP<const Teuchos::Comm<int>> comm;
  const mesh::HexMesh& mesh;
  NodeSpace space;
  DofLayout layout;
  SolidParameters solid;
  SystemOptions options;
  MasterControl control;
  std::array<double, 3> face_centre{};
  RigidFaceDirections directions;

  std::vector<std::int64_t> hex8;         // this rank's Hex8 elements (mesh ids)
  std::vector<std::size_t> hex13;         // this rank's Hex13 elements (indices into space.hex13_nodes)
  std::vector<std::size_t> faces;         // this rank's contact faces (indices into space.faces)
  std::vector<std::int64_t> local_nodes;  // nodes touched by them
  Teuchos::RCP<const Map> owned, overlap;     // unknowns: owned, and owned + shared (owned first)
  Teuchos::RCP<const Import> importer;
  Teuchos::RCP<FECrsGraph> graph;
  Teuchos::RCP<FECrsMatrix> matrix;
  Teuchos::RCP<FEMultiVector> residual;
  Teuchos::RCP<FEMultiVector> coupling;       // d f / d(prescribed master), one column per master
  Teuchos::RCP<Vector> state;                 // on the overlap map
  std::array<int, master_count> master_unknown{-1, -1, -1};
  double damping = 0.0;
  Teuchos::RCP<const Vector> damping_anchor;
  double half_contact_area = 0.0;

  DeviceView<int**> hex8_nodes, hex13_nodes;
  DeviceView<std::int64_t*> hex8_ids, hex13_ids;
  DeviceView<double* [3]> coordinates;
  DeviceView<int* [3]> node_unknown;
  DeviceView<double* [3]> node_offset;
  DeviceView<int* [2]> node_parent;
  DeviceView<int*> column_of;
  DeviceView<int[1]> dropped_entries;   // ElementScatter::dropped (made once Kokkos is up, with the views)
  ContactFaceViews contact_faces;

  Implementation(const mesh::HexMesh& mesh_, const mesh::Partition& partition, const Constraints& constraints,
                 const SolidParameters& solid_, Teuchos::RCP<const Teuchos::Comm<int>> comm_,
                 const SystemOptions& options_)
      : comm(std::move(comm_)), mesh(mesh_), space(make_node_space(mesh_, partition, options_.enrichment)),
        layout(make_dof_layout(space, constraints, partition.ranks)), solid(solid_), options(options_),
        face_centre(constraints.rigid_centre)
  {
    for (int i = 0; i < 3; ++i) {
      directions.lift[i] = constraints.lift_direction[i];
      directions.slide[i] = constraints.slide_direction[i];
    }
    const int rank = comm->getRank();
    for (auto e : space.hex8_elements)
      if (partition.element_owner[e] == rank) hex8.push_back(e);
    for (std::size_t k = 0; k < space.hex13_elements.size(); ++k)
      if (partition.element_owner[space.hex13_elements[k]] == rank) hex13.push_back(k);
    if (options.contact)
      for (std::size_t k = 0; k < space.faces.size(); ++k)
        if (partition.element_owner[space.face_elements[k]] == rank) faces.push_back(k);

    std::vector<int> local_of(space.node_count(), -1);
    auto touch = [&](std::int64_t n) {
      if (local_of[n] >= 0) return;
      local_of[n] = static_cast<int>(local_nodes.size());
      local_nodes.push_back(n);
    };
    for (auto e : hex8)
      for (auto n : mesh.elements[e]) touch(n);
    for (auto k : hex13)
      for (auto n : space.hex13_nodes[k]) touch(n);

    // Unknowns: owned block, then the shared ones this rank's elements touch.
    std::vector<GlobalOrdinal> owned_ids, shared_ids;
    for (auto id = layout.rank_offsets[rank]; id < layout.rank_offsets[rank + 1]; ++id) owned_ids.push_back(id);
    auto is_owned = [&](std::int64_t id) {
      return id >= layout.rank_offsets[rank] && id < layout.rank_offsets[rank + 1];
    };
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
    if (touches_face && std::find(master_unknown.begin(), master_unknown.end(), -1) != master_unknown.end())
      throw std::logic_error("end-face masters missing from the overlap map");

    build_views(local_of);
    dropped_entries = DeviceView<int[1]>("dropped tangent entries");
    build_graph();
    matrix = Teuchos::rcp(new FECrsMatrix(graph));
    residual = Teuchos::rcp(new FEMultiVector(owned, graph->getImporter(), 1));
    coupling = Teuchos::rcp(new FEMultiVector(owned, graph->getImporter(), master_count));
    state = Teuchos::rcp(new Vector(overlap));
    // Local column of every overlap unknown (the element kernels address matrix entries by local column).
    auto columns = Kokkos::create_mirror_view(column_of);
    const auto column_map = matrix->getColMap();
    for (std::size_t lid = 0; lid < overlap_ids.size(); ++lid)
      columns(lid) = column_map->getLocalElement(overlap_ids[lid]);
    Kokkos::deep_copy(column_of, columns);
  }

  template <std::size_t n>
  DeviceView<int**> connectivity(const std::string& label, const std::vector<std::array<std::int64_t, n>>& nodes,
                                 const std::vector<int>& local_of)
  {
    DeviceView<int**> view(label, nodes.size(), n);
    auto host = Kokkos::create_mirror_view(view);
    for (std::size_t e = 0; e < nodes.size(); ++e)
      for (std::size_t a = 0; a < n; ++a) host(e, a) = nodes[e][a] < 0 ? -1 : local_of[nodes[e][a]];
    Kokkos::deep_copy(view, host);
    return view;
  }

  void build_views(const std::vector<int>& local_of)
  {
    std::vector<std::array<std::int64_t, 8>> hex8_list;
    for (auto e : hex8) hex8_list.push_back(mesh.elements[e]);
    std::vector<std::array<std::int64_t, 13>> hex13_list;
    std::vector<std::int64_t> hex13_elements;
    for (auto k : hex13) {
      hex13_list.push_back(space.hex13_nodes[k]);
      hex13_elements.push_back(space.hex13_elements[k]);
    }
    std::vector<std::array<std::int64_t, 9>> face_list;
    for (auto k : faces) face_list.push_back(space.faces[k]);
    hex8_nodes = connectivity("hex8 nodes", hex8_list, local_of);
    hex13_nodes = connectivity("hex13 nodes", hex13_list, local_of);
    hex8_ids = to_device("hex8 ids", hex8);
    hex13_ids = to_device("hex13 ids", hex13_elements);

    const auto count = local_nodes.size();
    coordinates = DeviceView<double* [3]>("node coordinates", count);
    node_unknown = DeviceView<int* [3]>("node unknowns", count);
    node_offset = DeviceView<double* [3]>("rigid offsets", count);
    node_parent = DeviceView<int* [2]>("dependent parents", count);
    column_of = DeviceView<int*>("column of unknown", overlap->getNodeNumElements());
    auto h_coordinates = Kokkos::create_mirror_view(coordinates);
    auto h_unknown = Kokkos::create_mirror_view(node_unknown);
    auto h_offset = Kokkos::create_mirror_view(node_offset);
    auto h_parent = Kokkos::create_mirror_view(node_parent);
    for (std::size_t n = 0; n < count; ++n) {
      const auto node = local_nodes[n];
      for (int p = 0; p < 2; ++p) h_parent(n, p) = space.dependent[node] ? local_of[space.corners[node][p]] : -1;
      for (int i = 0; i < 3; ++i) {
        h_coordinates(n, i) = space.coordinates[node][i];
        h_offset(n, i) = space.coordinates[node][i] - face_centre[i];
        const auto id = layout.node_dofs[node][i];
        h_unknown(n, i) = layout.rigid[node]        ? rigid_component
                          : space.dependent[node]   ? dependent_component
                          : id < 0                  ? fixed_component
                                                    : overlap->getLocalElement(id);
      }
    }
    Kokkos::deep_copy(coordinates, h_coordinates);
    Kokkos::deep_copy(node_unknown, h_unknown);
    Kokkos::deep_copy(node_offset, h_offset);
    Kokkos::deep_copy(node_parent, h_parent);

    // Contact faces and their undeformed areas.
    contact_faces.face_nodes = space.face_nodes;
    contact_faces.count = static_cast<int>(face_list.size());
    contact_faces.coordinates = coordinates;
    contact_faces.anchors = coordinates;
    auto face_view = DeviceView<int* [9]>("contact faces", face_list.size());
    auto h_faces = Kokkos::create_mirror_view(face_view);
    std::vector<double> areas;
    for (std::size_t f = 0; f < face_list.size(); ++f) {
      for (int k = 0; k < 9; ++k) h_faces(f, k) = face_list[f][k] < 0 ? -1 : local_of[face_list[f][k]];
      areas.push_back(face_area(space, face_list[f]));
    }
    Kokkos::deep_copy(face_view, h_faces);
    contact_faces.nodes = face_view;
    contact_faces.areas = to_device("contact face areas", areas);
    half_contact_area = 0.0;
    for (const auto& face : space.faces) half_contact_area += face_area(space, face);
  }

  // The unknowns an element couples: its nodes' free components (a dependent node's through its corners) and,
  // if it touches the end face, both masters.
  template <class Nodes>
  std::vector<GlobalOrdinal> element_unknowns(const Nodes& nodes) const
  {
    std::vector<GlobalOrdinal> ids;
    bool rigid = false;
    for (auto n : nodes) {
      if (n < 0) continue;
      rigid |= layout.rigid[n] != 0;
      const auto& sources = space.dependent[n] ? std::array<std::int64_t, 2>{space.corners[n][0], space.corners[n][1]}
                                               : std::array<std::int64_t, 2>{n, -1};
      for (auto source : sources)
        if (source >= 0)
          for (auto id : layout.node_dofs[source])
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
    auto add_clique = [&](const std::vector<GlobalOrdinal>& ids) {
      for (auto row : ids) {
        auto& entries = rows[overlap->getLocalElement(row)];
        entries.insert(entries.end(), ids.begin(), ids.end());
      }
    };
    for (auto e : hex8) add_clique(element_unknowns(mesh.elements[e]));
    for (auto k : hex13) add_clique(element_unknowns(space.hex13_nodes[k]));
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

  ElementScatter make_scatter(const std::array<double, master_count>& masters, bool with_matrix)
  {
    ElementScatter scatter;
    scatter.column_of = column_of;
    scatter.node_unknown = node_unknown;
    scatter.node_offset = node_offset;
    scatter.node_parent = node_parent;
    for (int m = 0; m < master_count; ++m) {
      scatter.master_unknown[m] = master_unknown[m];
      scatter.master_prescribed[m] = control.prescribed[m];
      scatter.masters[m] = masters[m];
    }
    scatter.directions = directions;
    scatter.with_residual = true;
    scatter.with_matrix = with_matrix;
    scatter.dropped = dropped_entries;
    if (with_matrix) Kokkos::deep_copy(dropped_entries, 0);
    scatter.state = state->getLocalViewDevice(Tpetra::Access::ReadOnly);
    scatter.residual = residual->getLocalViewDevice(Tpetra::Access::ReadWrite);
    if (with_matrix) {
      scatter.matrix = matrix->getLocalMatrixDevice();
      scatter.coupling = coupling->getLocalViewDevice(Tpetra::Access::ReadWrite);
    }
    return scatter;
  }

  std::array<double, master_count> master_values(const Vector& x) const
  {
    std::array<double, master_count> values{};
    for (int m = 0; m < master_count; ++m) values[m] = master_value(x, Master(m));
    return values;
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

  template <class Shape>
  double solid_block(const char* label, const ElementScatter& scatter, const DeviceView<int**>& nodes,
                     const DeviceView<std::int64_t*>& ids, const DeviceView<std::int64_t[1]>& inverted)
  {
    double energy = 0.0;
    const int order = Shape::nodes == 13 ? std::max(solid.quadrature_order, 3) : solid.quadrature_order;
    SolidKernel<Shape> kernel{scatter, nodes, ids, coordinates, inverted,
                              laws::NeoHookean::from_young(solid.young, solid.poisson), order};
    Kokkos::parallel_reduce(label, Kokkos::RangePolicy<execution_space>(0, static_cast<int>(nodes.extent(0))),
                            kernel, energy);
    return energy;
  }

  // Residual (and tangent) of the state x: the bulk and contact blocks scattered into the global system, the
  // constraints' rows, the totals over the ranks, then the reactions.
  Evaluation evaluate(const Vector& x, Vector* out_residual, bool with_jacobian)
  {
    state->doImport(x, *importer, Tpetra::INSERT);
    const auto masters = master_values(x);
    Tpetra::beginAssembly(*residual);
    residual->putScalar(0.0);
    if (with_jacobian) {
      Tpetra::beginAssembly(*matrix, *coupling);
      matrix->setAllToScalar(0.0);
      coupling->putScalar(0.0);
    }
    DeviceView<std::int64_t[1]> inverted("inverted element");
    double energy = 0.0;
    ContactTotals contact;
    {
      const auto scatter = make_scatter(masters, with_jacobian);
      energy = assemble_bulk(scatter, with_jacobian, inverted);
      if (options.contact) contact = assemble_contact(scatter, with_jacobian);
      if (with_jacobian && damping > 0.0) add_damping_diagonal();
      if (with_jacobian) add_prescribed_diagonals();
      if (with_jacobian) check_no_entry_dropped(scatter);
    }
    {
      Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: assembly communication"));
      Tpetra::endAssembly(*residual);
      if (with_jacobian) Tpetra::endAssembly(*matrix, *coupling);
    }
    auto result = totals_over_ranks(energy, contact, inverted);
    reactions_and_constraint_rows(x, result);
    if (out_residual) out_residual->assign(*residual);
    return result;
  }

  double assemble_bulk(const ElementScatter& scatter, bool with_jacobian, const DeviceView<std::int64_t[1]>& inverted)
  {
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer(
        with_jacobian ? "spatula: assembly bulk (residual + tangent)" : "spatula: assembly bulk (residual)"));
    double energy = 0.0;
    energy += solid_block<elements::Hex8Shape>("spatula: solid hex8 assembly", scatter, hex8_nodes, hex8_ids, inverted);
    energy +=
        solid_block<elements::Hex13Shape>("spatula: solid hex13 assembly", scatter, hex13_nodes, hex13_ids, inverted);
    Kokkos::fence();
    return energy;
  }

  ContactTotals assemble_contact(const ElementScatter& scatter, bool with_jacobian)
  {
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer(
        with_jacobian ? "spatula: assembly contact (residual + tangent)" : "spatula: assembly contact (residual)"));
    const auto contact = options.contact->assemble(contact_faces, scatter);
    Kokkos::fence();
    return contact;
  }

  // Proximal damping on the diagonal of every owned row that is not a prescribed master.
  void add_damping_diagonal()
  {
    AddToDiagonal add{matrix->getLocalMatrixDevice(), column_of, damping, {}};
    for (int m = 0; m < master_count; ++m)
      add.skip[m] = control.prescribed[m] ? owned->getLocalElement(layout.masters[m]) : -1;
    const int rows = static_cast<int>(owned->getNodeNumElements());
    Kokkos::parallel_for("spatula: proximal damping", Kokkos::RangePolicy<execution_space>(0, rows), add);
  }

  // Identity rows of prescribed masters (their owner adds the diagonal once).
  void add_prescribed_diagonals()
  {
    for (int m = 0; m < master_count; ++m) {
      const int unknown = owned->getLocalElement(layout.masters[m]);
      if (!control.prescribed[m] || unknown < 0) continue;
      const AddToDiagonal add{matrix->getLocalMatrixDevice(), column_of, 1.0, {-1, -1, -1}};
      Kokkos::parallel_for("spatula: prescribed master diagonal",
                           Kokkos::RangePolicy<execution_space>(unknown, unknown + 1), add);
    }
    Kokkos::fence();
  }

  static void check_no_entry_dropped(const ElementScatter& scatter)
  {
    auto dropped = Kokkos::create_mirror_view(scatter.dropped);
    Kokkos::deep_copy(dropped, scatter.dropped);
    if (dropped(0) != 0)
      throw std::logic_error(std::to_string(dropped(0)) + " tangent entries fell outside the matrix graph");
  }

  // Energies, contact face counts and the inverted-element flag summed over the ranks.
  Evaluation totals_over_ranks(double energy, const ContactTotals& contact, const DeviceView<std::int64_t[1]>& inverted)
  {
    Evaluation result;
    auto h_inverted = Kokkos::create_mirror_view(inverted);
    Kokkos::deep_copy(h_inverted, inverted);
    std::int64_t bad = h_inverted(0);
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, bad, Teuchos::outArg(bad));
    double sums[2] = {energy, contact.energy}, totals[2];
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 2, sums, totals);
    int counts[2] = {contact.active_faces, contact.skipped_faces}, count_totals[2];
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 2, counts, count_totals);
    result.internal_energy = totals[0];
    result.contact_energy = totals[1];
    result.active_contact_faces = count_totals[0];
    result.skipped_contact_faces = count_totals[1];
    result.admissible = bad == 0;
    result.inverted_element = bad - 1;
    return result;
  }

  // Reactions: the master rows' internal forces, then prescribed rows become identity rows (residual 0); the
  // proximal damping's force eta (x - anchor) on every other row.
  void reactions_and_constraint_rows(const Vector& x, Evaluation& result)
  {
    auto values = residual->getDataNonConst(0);
    for (int m = 0; m < master_count; ++m) {
      const int unknown = owned->getLocalElement(layout.masters[m]);
      double reaction = unknown >= 0 ? values[unknown] : 0.0;
      Teuchos::broadcast(*comm, 0, Teuchos::outArg(reaction));
      result.master_residual[m] = reaction;
      if (unknown >= 0 && control.prescribed[m]) values[unknown] = 0.0;
      if (!control.prescribed[m] && control.applied[m] != 0.0) {   // a dead load on a free master
        if (unknown >= 0) values[unknown] -= control.applied[m];
        result.load_potential -= control.applied[m] * master_value(x, static_cast<Master>(m));
      }
    }
    if (damping > 0.0) {
      const auto anchor = damping_anchor->getData(0);
      const auto state_values = x.getData(0);
      for (std::size_t i = 0; i < owned->getNodeNumElements(); ++i) values[i] += damping * (state_values[i] - anchor[i]);
      for (int m = 0; m < master_count; ++m) {
        const int unknown = owned->getLocalElement(layout.masters[m]);
        if (unknown >= 0 && control.prescribed[m]) values[unknown] = 0.0;
      }
    }
  }
};

DiscreteSystem::DiscreteSystem(const mesh::HexMesh& mesh, const mesh::Partition& partition,
                               const Constraints& constraints, const SolidParameters& solid,
                               Teuchos::RCP<const Teuchos::Comm<int>> comm, const SystemOptions& options)
    : implementation_(std::make_unique<Implementation>(mesh, partition, constraints, solid, std::move(comm), options))
{
}

DiscreteSystem::~DiscreteSystem() = default;

Teuchos::RCP<const Map> DiscreteSystem::owned_map() const { return implementation_->owned; }
Teuchos::RCP<Vector> DiscreteSystem::create_vector() const { return Teuchos::rcp(new Vector(implementation_->owned)); }
Teuchos::RCP<CrsMatrix> DiscreteSystem::jacobian() const { return implementation_->matrix; }
const DofLayout& DiscreteSystem::layout() const { return implementation_->layout; }
const NodeSpace& DiscreteSystem::nodes() const { return implementation_->space; }
const MultiVector& DiscreteSystem::load_derivatives() const { return *implementation_->coupling; }

void DiscreteSystem::set_damping(double eta, Teuchos::RCP<const Vector> anchor)
{
  implementation_->damping = eta;
  implementation_->damping_anchor = std::move(anchor);
}

void DiscreteSystem::set_contact_anchors(const Vector& x)
{
  auto& impl = *implementation_;
  const auto u = space_displacements(x);   // collective
  DeviceView<double* [3]> anchors("contact anchors", impl.local_nodes.size());
  auto host = Kokkos::create_mirror_view(anchors);
  for (std::size_t n = 0; n < impl.local_nodes.size(); ++n)
    for (int i = 0; i < 3; ++i) {
      const auto node = impl.local_nodes[n];
      host(n, i) = impl.space.coordinates[node][i] + u[3 * node + i];
    }
  Kokkos::deep_copy(anchors, host);
  impl.contact_faces.anchors = anchors;
}

double DiscreteSystem::mean_diagonal() const
{
  const auto& matrix = *implementation_->matrix;
  Vector diagonal(matrix.getRowMap());
  matrix.getLocalDiagCopy(diagonal);
  return diagonal.norm1() / static_cast<double>(diagonal.getGlobalLength());
}
double DiscreteSystem::contact_area() const { return implementation_->half_contact_area; }
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

NodeBlocks DiscreteSystem::node_blocks() const
{
  const auto& impl = *implementation_;
  const auto& layout = impl.layout;
  const auto& coordinates = impl.space.coordinates;
  const auto& offsets = layout.rank_offsets;
  const auto rank_of = [&offsets](std::int64_t unknown) {
    return static_cast<int>(std::upper_bound(offsets.begin(), offsets.end(), unknown) - offsets.begin()) - 1;
  };
  // The blocks of each rank in node order (-1: the masters' block, on the rank owning the masters).
  std::vector<std::vector<std::int64_t>> blocks(offsets.size() - 1);
  for (std::int64_t n = 0; n < impl.space.node_count(); ++n)
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
  const int rank = impl.comm->getRank();
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
                                    Teuchos::ArrayView<const GlobalOrdinal>(owned_rows), 0, impl.comm));
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

void DiscreteSystem::set_displacements(Vector& x, const std::vector<double>& u) const
{
  const auto& impl = *implementation_;
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

std::vector<double> DiscreteSystem::node_displacements(const Vector& x) const
{
  const auto& impl = *implementation_;
  auto all = space_displacements(x);
  all.resize(3 * impl.space.mesh_nodes);
  return all;
}

std::vector<double> DiscreteSystem::space_displacements(const Vector& x) const
{
  const auto& impl = *implementation_;
  return all_displacements(*this, x, impl.space, impl.layout, impl.face_centre, impl.directions, *impl.comm);
}

void DiscreteSystem::set_space_displacements(Vector& x, const std::vector<double>& u) const
{
  const auto& impl = *implementation_;
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

std::vector<double> DiscreteSystem::element_cauchy_trace(const Vector& x) const
{
  const auto& impl = *implementation_;
  const auto u = space_displacements(x);
  const auto law = laws::NeoHookean::from_young(impl.solid.young, impl.solid.poisson);
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
  for (auto e : impl.hex8) local[e] = trace(impl.mesh.elements[e], elements::Hex8Shape{}, impl.solid.quadrature_order);
  for (auto k : impl.hex13)
    local[impl.space.hex13_elements[k]] =
        trace(impl.space.hex13_nodes[k], elements::Hex13Shape{}, std::max(impl.solid.quadrature_order, 3));
  Teuchos::reduceAll(*impl.comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), global.data());
  return global;
}

}  // namespace spatula::discretization
