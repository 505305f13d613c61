#pragma once
// What one rank holds of the discrete system, fixed for a run: its elements and contact faces (from the partition),
// the maps of its unknowns (owned, and owned + shared with owned first, as Tpetra's FE classes want), the FE graph
// built once with exact row lengths, and the device views the assembly kernels read (connectivity in local node
// ids, reference coordinates, each node component's unknown or constraint, the local column of every unknown).
#include "discretization/contact_model.hpp"
#include "discretization/dof_layout.hpp"
#include "discretization/node_space.hpp"
#include "discretization/rigid_face.hpp"
#include "discretization/tpetra_types.hpp"

#include <Teuchos_Comm.hpp>

#include <array>
#include <vector>

namespace spatula::discretization {

struct SystemTopology {
  SystemTopology(const mesh::HexMesh& mesh, const mesh::Partition& partition, const Constraints& constraints,
                 Enrichment enrichment, bool with_contact, Teuchos::RCP<const Teuchos::Comm<int>> comm);

  Teuchos::RCP<const Teuchos::Comm<int>> comm;
  const mesh::HexMesh& mesh;
  NodeSpace space;
  DofLayout layout;
  std::array<double, 3> face_centre{};
  RigidFaceDirections directions;

  std::vector<std::int64_t> hex8;         // this rank's Hex8 elements (mesh ids)
  std::vector<std::size_t> hex13;         // this rank's Hex13 elements (indices into space.hex13_nodes)
  std::vector<std::size_t> faces;         // this rank's contact faces (indices into space.faces)
  std::vector<std::int64_t> local_nodes;  // nodes touched by them
  Teuchos::RCP<const Map> owned, overlap;     // unknowns: owned, and owned + shared (owned first)
  Teuchos::RCP<const Import> importer;
  Teuchos::RCP<FECrsGraph> graph;
  std::array<int, master_count> master_unknown{-1, -1, -1};   // the masters' local ids in `overlap` (-1: absent)
  double half_contact_area = 0.0;   // undeformed, over every contact face of the half model [nm^2]

  DeviceView<int**> hex8_nodes, hex13_nodes;
  DeviceView<std::int64_t*> hex8_ids, hex13_ids;
  DeviceView<double* [3]> coordinates;
  DeviceView<int* [3]> node_unknown;
  DeviceView<double* [3]> node_offset;
  DeviceView<int* [2]> node_parent;
  DeviceView<int*> column_of;   // the matrix's local column of every overlap unknown
  ContactFaceViews contact_faces;

private:
  template <std::size_t n>
  DeviceView<int**> connectivity(const std::string& label, const std::vector<std::array<std::int64_t, n>>& nodes,
                                 const std::vector<int>& local_of);
  void build_views(const std::vector<int>& local_of);
  template <class Nodes>
  std::vector<GlobalOrdinal> element_unknowns(const Nodes& nodes) const;
  void build_graph();
};

}  // namespace spatula::discretization
