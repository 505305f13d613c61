#pragma once
// Mesh and field output as HDF5 data with an XDMF index that ParaView opens.
//
// <name>.h5 holds /mesh (coordinates, hexahedra, part and rank per element, node and side sets, the contact
// faces as quadrilaterals) and one group /states/<k> per written state (deformed coordinates, nodal vectors and
// cell scalars). Three XDMF files index it, one grid each so every array is defined on all of its cells:
// <name>.xmf (the volume mesh), <name>_contact.xmf (the contact surface) and <name>_states.xmf (a temporal
// collection of the states, rewritten after every state so an unfinished run is still readable).
#include "mesh/hex_mesh.hpp"
#include "mesh/partition.hpp"

#include <map>
#include <string>
#include <vector>

namespace spatula::io {

// A state to write: nodal vectors (N x 3, row-major) and cell scalars (one per element), by name.
struct FieldState {
  double time = 0.0;   // the load parameter (rotation in degrees, or u_z in nm)
  std::vector<double> displacement;   // N x 3
  std::map<std::string, std::vector<double>> cell_scalars;
  std::map<std::string, std::vector<double>> node_vectors;
};

class XdmfOutput {
public:
  // Writes the mesh at once into `directory`/<name>.h5 and its index files. The XDMF files refer to the HDF5
  // file by its base name, so the directory can be moved.
  XdmfOutput(const std::string& directory, const std::string& name, const mesh::HexMesh& mesh,
             const mesh::Partition& partition);

  // Goes on with the output of a stopped run in `directory`: keeps its first `keep_states` states (each written with
  // the cell scalars and node vectors named) and drops any later ones. Throws if the file cannot be read or lacks
  // one of the kept states (then make a new output).
  XdmfOutput(const std::string& directory, const std::string& name, const mesh::HexMesh& mesh, int keep_states,
             const std::vector<std::string>& cell_scalar_names, const std::vector<std::string>& node_vector_names);

  void add_state(const FieldState& state);
  int state_count() const { return static_cast<int>(times_.size()); }

private:
  void write_mesh_index() const;
  void write_states_index() const;

  std::string directory_, name_, h5_path_, h5_name_;
  std::int64_t nodes_ = 0, elements_ = 0, contact_faces_ = 0;
  std::vector<double> reference_;   // N x 3
  std::vector<double> times_;
  std::vector<std::vector<std::string>> cell_scalar_names_, node_vector_names_;
};

}  // namespace spatula::io
