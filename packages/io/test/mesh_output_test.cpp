// HDF5/XDMF output round trip, and the all-or-nothing output directory.
#include "hdf5_file.hpp"
#include "mesh_output.hpp"
#include "output_directory.hpp"
#include "spatula_mesher.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace spatula;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name)
{
  const fs::path path = fs::temp_directory_path() / ("spatula-io-test-" + std::to_string(::getpid())) / name;
  fs::remove_all(path);
  fs::create_directories(path.parent_path());
  return path;
}

std::string read(const fs::path& file)
{
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST(Hdf5File, RoundTripOfTablesAndScalars)
{
  const auto file_name = scratch("round-trip.h5").string();
  {
    io::Hdf5File file(file_name, io::Hdf5File::Mode::create);
    file.write("/a/b/values", std::vector<double>{1.5, -2.0, 3.25, 4.0}, 2);
    file.write("/a/ids", std::vector<std::int64_t>{7, 8, 9});
  }
  io::Hdf5File file(file_name, io::Hdf5File::Mode::read);
  EXPECT_EQ(file.read_doubles("/a/b/values"), (std::vector<double>{1.5, -2.0, 3.25, 4.0}));
  EXPECT_EQ(file.read_integers("/a/ids"), (std::vector<std::int64_t>{7, 8, 9}));
  EXPECT_TRUE(file.exists("/a/b/values"));
  EXPECT_FALSE(file.exists("/a/c/values"));
  EXPECT_THROW(file.read_doubles("/missing"), std::runtime_error);
}

TEST(XdmfOutput, MeshAndStatesAreIndexed)
{
  const auto directory = scratch("xdmf");
  fs::create_directories(directory);
  const geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  const auto mesh = mesh::mesh_spatula(shape, mesh::MeshParameters{});
  const auto partition = mesh::partition_mesh(mesh, 2);
  io::XdmfOutput output(directory.string(), "mesh", mesh, partition);
  io::FieldState state;
  state.time = 10.0;
  state.displacement.assign(3 * mesh.node_count(), 0.5);
  state.cell_scalars["I1"].assign(mesh.element_count(), 0.25);
  output.add_state(state);

  io::Hdf5File file((directory / "mesh.h5").string(), io::Hdf5File::Mode::read);
  const auto coordinates = file.read_doubles("/mesh/coordinates");
  ASSERT_EQ(coordinates.size(), 3 * std::size_t(mesh.node_count()));
  EXPECT_DOUBLE_EQ(coordinates[3 * 7 + 2], mesh.coordinates[7][2]);
  const auto hexahedra = file.read_integers("/mesh/hexahedra");
  ASSERT_EQ(hexahedra.size(), 8 * std::size_t(mesh.element_count()));
  EXPECT_EQ(hexahedra[8 * 5 + 3], mesh.elements[5][3]);
  EXPECT_EQ(file.read_integers("/mesh/node_sets/contact").size(), mesh.nodes(mesh::Boundary::contact).size());
  const auto deformed = file.read_doubles("/states/000000/coordinates");
  EXPECT_DOUBLE_EQ(deformed[4], mesh.coordinates[1][1] + 0.5);
  EXPECT_EQ(file.read_doubles("/states/000000/I1").size(), std::size_t(mesh.element_count()));

  const auto volume = read(directory / "mesh.xmf");
  EXPECT_NE(volume.find("NumberOfElements=\"" + std::to_string(mesh.element_count()) + "\""), std::string::npos);
  EXPECT_NE(volume.find("mesh.h5:/mesh/hexahedra"), std::string::npos);
  const auto contact = read(directory / "mesh_contact.xmf");
  EXPECT_NE(contact.find("Quadrilateral"), std::string::npos);
  const auto states = read(directory / "mesh_states.xmf");
  EXPECT_NE(states.find("<Time Value=\"10\"/>"), std::string::npos);
  EXPECT_NE(states.find("/states/000000/I1"), std::string::npos);
}

TEST(OutputDirectory, CommitReplacesAbandonLeavesNothingThatLooksComplete)
{
  const auto path = scratch("run");
  {
    io::OutputDirectory directory(path.string());
    std::ofstream(directory.file("a.txt")) << "first";
    EXPECT_FALSE(fs::exists(path));
    directory.commit();
  }
  EXPECT_EQ(read(path / "a.txt"), "first");
  {
    io::OutputDirectory directory(path.string());
    std::ofstream(directory.file("a.txt")) << "second";
    // destroyed without commit: an error happened
  }
  EXPECT_EQ(read(path / "a.txt"), "first");
  EXPECT_TRUE(fs::exists(path.string() + ".incomplete"));
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
}
