#include "discretization/system_topology.hpp"

#include "elements/gauss_rule.hpp"
#include "elements/quadrilateral_shape.hpp"

#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Assembly_Helpers.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spatula::discretization {

namespace {

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

SystemTopology::SystemTopology(const mesh::HexMesh& mesh_, const mesh::Partition& partition,
                               const Constraints& constraints, Enrichment enrichment, bool with_contact,
                               Teuchos::RCP<const Teuchos::Comm<int>> comm_)
    : comm(std::move(comm_)), mesh(mesh_), space(make_node_space(mesh_, partition, enrichment)),
      layout(make_dof_layout(space, constraints, partition.ranks)), face_centre(constraints.rigid_centre)
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
  if (with_contact)
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
  build_graph();
  // Local column of every overlap unknown (the element kernels address matrix entries by local column; a matrix
  // made on the graph has the graph's column map).
  auto columns = Kokkos::create_mirror_view(column_of);
  const auto column_map = graph->getColMap();
  for (std::size_t lid = 0; lid < overlap_ids.size(); ++lid)
    columns(lid) = column_map->getLocalElement(overlap_ids[lid]);
  Kokkos::deep_copy(column_of, columns);
}

template <std::size_t n>
DeviceView<int**> SystemTopology::connectivity(const std::string& label,
                                            const std::vector<std::array<std::int64_t, n>>& nodes,
                                            const std::vector<int>& local_of)
{
  DeviceView<int**> view(label, nodes.size(), n);
  auto host = Kokkos::create_mirror_view(view);
  for (std::size_t e = 0; e < nodes.size(); ++e)
    for (std::size_t a = 0; a < n; ++a) host(e, a) = nodes[e][a] < 0 ? -1 : local_of[nodes[e][a]];
  Kokkos::deep_copy(view, host);
  return view;
}

void SystemTopology::build_views(const std::vector<int>& local_of)
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
std::vector<GlobalOrdinal> SystemTopology::element_unknowns(const Nodes& nodes) const
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

void SystemTopology::build_graph()
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

}  // namespace spatula::discretization
