#include "io/mesh_output.hpp"

#include "io/checked_write.hpp"

#include "io/hdf5_file.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace spatula::io {

namespace {

std::string state_group(int index)
{
  char name[32];
  std::snprintf(name, sizeof(name), "/states/%06d", index);
  return name;
}

std::string data_item(const std::string& dimensions, const std::string& number_type, int precision,
                      const std::string& location)
{
  std::ostringstream out;
  out << "<DataItem Dimensions=\"" << dimensions << "\" NumberType=\"" << number_type << "\" Precision=\""
      << precision << "\" Format=\"HDF\">" << location << "</DataItem>";
  return out.str();
}

}  // namespace

XdmfOutput::XdmfOutput(const std::string& directory, const std::string& name, const mesh::HexMesh& mesh,
                       const mesh::Partition& partition)
    : directory_(directory), name_(name), h5_path_((std::filesystem::path(directory) / (name + ".h5")).string()),
      h5_name_(name + ".h5"), nodes_(mesh.node_count()), elements_(mesh.element_count())
{
  Hdf5File file(h5_path_, Hdf5File::Mode::create);
  for (const auto& x : mesh.coordinates) reference_.insert(reference_.end(), x.begin(), x.end());
  file.write("/mesh/coordinates", reference_, 3);
  std::vector<std::int64_t> connectivity;
  for (const auto& element : mesh.elements) connectivity.insert(connectivity.end(), element.begin(), element.end());
  file.write("/mesh/hexahedra", connectivity, 8);
  std::vector<int> parts;
  for (auto part : mesh.parts) parts.push_back(static_cast<int>(part));
  file.write("/mesh/part", parts);
  file.write("/mesh/rank", partition.element_owner);
  for (int b = 0; b < mesh::boundary_count; ++b) {
    const auto boundary = mesh::Boundary(b);
    const std::string name = mesh::boundary_name(boundary);
    file.write("/mesh/node_sets/" + name, mesh.nodes(boundary));
    std::vector<int> indicator(mesh.node_count(), 0);
    for (auto n : mesh.nodes(boundary)) indicator[n] = 1;
    file.write("/mesh/node_indicators/" + name, indicator);
    std::vector<std::int64_t> sides;
    for (const auto& side : mesh.sides(boundary)) {
      sides.push_back(side.element);
      sides.push_back(side.face);
    }
    file.write("/mesh/side_sets/" + name, sides, 2);
  }
  std::vector<std::int64_t> quads;
  for (const auto& side : mesh.sides(mesh::Boundary::contact)) {
    const auto nodes = mesh.side_nodes(side);
    quads.insert(quads.end(), nodes.begin(), nodes.end());
  }
  contact_faces_ = static_cast<std::int64_t>(mesh.sides(mesh::Boundary::contact).size());
  file.write("/mesh/contact_quadrilaterals", quads, 4);
  file.close();
  write_mesh_index();
}

XdmfOutput::XdmfOutput(const std::string& directory, const std::string& name, const mesh::HexMesh& mesh,
                       int keep_states, const std::vector<std::string>& cell_scalar_names,
                       const std::vector<std::string>& node_vector_names)
    : directory_(directory), name_(name), h5_path_((std::filesystem::path(directory) / (name + ".h5")).string()),
      h5_name_(name + ".h5"), nodes_(mesh.node_count()), elements_(mesh.element_count()),
      contact_faces_(static_cast<std::int64_t>(mesh.sides(mesh::Boundary::contact).size()))
{
  for (const auto& x : mesh.coordinates) reference_.insert(reference_.end(), x.begin(), x.end());
  Hdf5File file(h5_path_, Hdf5File::Mode::append);
  if (file.read_doubles("/mesh/coordinates") != reference_)
    throw std::runtime_error("'" + h5_path_ + "' holds another mesh");
  for (int k = 0; k < keep_states; ++k) {
    const std::string group = state_group(k);
    for (const auto* fields : {&cell_scalar_names, &node_vector_names})
      for (const auto& field : *fields)
        if (!file.exists(group + "/" + field)) throw std::runtime_error("'" + h5_path_ + "' lacks " + group + "/" + field);
    const auto time = file.read_doubles(group + "/time");
    if (time.size() != 1) throw std::runtime_error("'" + h5_path_ + "' lacks " + group + "/time");
    times_.push_back(time[0]);
    cell_scalar_names_.push_back(cell_scalar_names);
    node_vector_names_.push_back(node_vector_names);
  }
  for (int k = keep_states; file.exists(state_group(k)); ++k) file.remove(state_group(k));
  file.close();
  write_states_index();
}

void XdmfOutput::add_state(const FieldState& state)
{
  const int index = state_count();
  const std::string group = state_group(index);
  {
    Hdf5File file(h5_path_, Hdf5File::Mode::append);
    std::vector<double> deformed = reference_;
    for (std::size_t i = 0; i < deformed.size(); ++i) deformed[i] += state.displacement[i];
    file.write(group + "/coordinates", deformed, 3);
    file.write(group + "/displacement", state.displacement, 3);
    file.write(group + "/time", std::vector<double>{state.time});
    for (const auto& [name, values] : state.cell_scalars) file.write(group + "/" + name, values);
    for (const auto& [name, values] : state.node_vectors) file.write(group + "/" + name, values, 3);
    file.close();
  }
  times_.push_back(state.time);
  std::vector<std::string> cells, vectors;
  for (const auto& entry : state.cell_scalars) cells.push_back(entry.first);
  for (const auto& entry : state.node_vectors) vectors.push_back(entry.first);
  cell_scalar_names_.push_back(cells);
  node_vector_names_.push_back(vectors);
  write_states_index();
}

namespace {

// Writes XDMF text for one file: grids built with the helpers below, then `save` replaces the file atomically.
class XdmfText {
public:
  XdmfText(std::string h5_name, std::int64_t nodes, std::int64_t elements)
      : h5_(std::move(h5_name)), nodes_(std::to_string(nodes)), elements_(std::to_string(elements))
  {
    out_ << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
  }
  std::ostringstream& out() { return out_; }
  const std::string& nodes() const { return nodes_; }
  const std::string& elements() const { return elements_; }

  void hexahedra(const std::string& indent)
  {
    out_ << indent << "<Topology TopologyType=\"Hexahedron\" NumberOfElements=\"" << elements_ << "\">\n"
         << indent << " " << data_item(elements_ + " 8", "Int", 8, h5_ + ":/mesh/hexahedra") << "\n"
         << indent << "</Topology>\n";
  }
  void geometry(const std::string& indent, const std::string& dataset)
  {
    out_ << indent << "<Geometry GeometryType=\"XYZ\">\n"
         << indent << " " << data_item(nodes_ + " 3", "Float", 8, h5_ + ":" + dataset) << "\n"
         << indent << "</Geometry>\n";
  }
  void attribute(const std::string& indent, const std::string& name, bool vector, bool on_cells, bool integer,
                 const std::string& dataset)
  {
    const std::string dims = (on_cells ? elements_ : nodes_) + (vector ? " 3" : "");
    out_ << indent << "<Attribute Name=\"" << name << "\" AttributeType=\"" << (vector ? "Vector" : "Scalar")
         << "\" Center=\"" << (on_cells ? "Cell" : "Node") << "\">\n"
         << indent << " " << data_item(dims, integer ? "Int" : "Float", integer ? 4 : 8, h5_ + ":" + dataset) << "\n"
         << indent << "</Attribute>\n";
  }
  void save(const std::string& path)
  {
    out_ << " </Domain>\n</Xdmf>\n";
    const std::string temporary = path + ".tmp";
    try {
      write_text_file(temporary, out_.str());
    } catch (...) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw;
    }
    rename_path(temporary, path);
  }

private:
  std::string h5_, nodes_, elements_;
  std::ostringstream out_;
};

}  // namespace

void XdmfOutput::write_mesh_index() const
{
  const auto path = [&](const std::string& suffix) {
    return (std::filesystem::path(directory_) / (name_ + suffix)).string();
  };
  XdmfText volume(h5_name_, nodes_, elements_);
  volume.out() << "  <Grid Name=\"spatula mesh\" GridType=\"Uniform\">\n";
  volume.hexahedra("   ");
  volume.geometry("   ", "/mesh/coordinates");
  volume.attribute("   ", "part", false, true, true, "/mesh/part");
  volume.attribute("   ", "rank", false, true, true, "/mesh/rank");
  for (int b = 0; b < mesh::boundary_count; ++b) {
    const std::string name = mesh::boundary_name(mesh::Boundary(b));
    volume.attribute("   ", name, false, false, true, "/mesh/node_indicators/" + name);
  }
  volume.out() << "  </Grid>\n";
  volume.save(path(".xmf"));

  XdmfText contact(h5_name_, nodes_, elements_);
  const std::string faces = std::to_string(contact_faces_);
  contact.out() << "  <Grid Name=\"contact surface\" GridType=\"Uniform\">\n"
                << "   <Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"" << faces << "\">\n"
                << "    " << data_item(faces + " 4", "Int", 8, h5_name_ + ":/mesh/contact_quadrilaterals") << "\n"
                << "   </Topology>\n";
  contact.geometry("   ", "/mesh/coordinates");
  contact.out() << "  </Grid>\n";
  contact.save(path("_contact.xmf"));
}

void XdmfOutput::write_states_index() const
{
  XdmfText states(h5_name_, nodes_, elements_);
  states.out() << "  <Grid Name=\"states\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < times_.size(); ++k) {
    const std::string group = state_group(static_cast<int>(k));
    states.out() << "   <Grid Name=\"state " << k << "\" GridType=\"Uniform\">\n"
                 << "    <Time Value=\"" << times_[k] << "\"/>\n";
    states.hexahedra("    ");
    states.geometry("    ", group + "/coordinates");
    states.attribute("    ", "displacement", true, false, false, group + "/displacement");
    states.attribute("    ", "part", false, true, true, "/mesh/part");
    for (const auto& name : cell_scalar_names_[k]) states.attribute("    ", name, false, true, false, group + "/" + name);
    for (const auto& name : node_vector_names_[k]) states.attribute("    ", name, true, false, false, group + "/" + name);
    states.out() << "   </Grid>\n";
  }
  states.out() << "  </Grid>\n";
  states.save((std::filesystem::path(directory_) / (name_ + "_states.xmf")).string());
}

}  // namespace spatula::io
