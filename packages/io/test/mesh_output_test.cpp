// HDF5/XDMF output round trip, and the all-or-nothing output directory.
#include "io/hdf5_file.hpp"
#include "io/mesh_output.hpp"
#include "io/output_directory.hpp"
#include "mesh/spatula_mesher.hpp"

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

TEST(OutputDirectory, RefusesWhatItDidNotWriteAndWhatHoldsTheWorkingDirectory)
{
  const auto base = scratch("refusals");
  fs::create_directories(base / "user");
  std::ofstream(base / "user" / "data.txt") << "the user's";
  std::ofstream(base / "file") << "the user's";
  const auto working = fs::current_path();
  fs::current_path(base);
  EXPECT_TRUE(io::OutputDirectory::refusal(".", true));
  EXPECT_TRUE(io::OutputDirectory::refusal("./", true));
  EXPECT_TRUE(io::OutputDirectory::refusal("..", true));
  EXPECT_TRUE(io::OutputDirectory::refusal("/", true));
  EXPECT_TRUE(io::OutputDirectory::refusal("", true));
  EXPECT_TRUE(io::OutputDirectory::refusal("user", true));
  EXPECT_TRUE(io::OutputDirectory::refusal("file", true));
  EXPECT_TRUE(io::OutputDirectory::refusal(std::string(256, 'x'), true));
  EXPECT_FALSE(io::OutputDirectory::refusal("new/deeper", true));
  EXPECT_FALSE(fs::exists("new"));   // refusal looks, it creates nothing
  {
    io::OutputDirectory ours("ours/");   // a trailing separator names the same directory
    EXPECT_TRUE(fs::exists("ours.partial/.spatula-output"));
    ours.commit();
  }
  EXPECT_TRUE(fs::exists(fs::path("ours") / io::OutputDirectory::marker_name));
  EXPECT_FALSE(io::OutputDirectory::refusal("ours", true));   // an earlier result of ours may be replaced
  EXPECT_TRUE(io::OutputDirectory::refusal("ours", false));   // unless overwriting is off
  EXPECT_TRUE(io::OutputDirectory::would_replace("ours", "ours/scene.xml"));
  EXPECT_TRUE(io::OutputDirectory::would_replace("ours", "ours.incomplete/checkpoints.h5"));
  EXPECT_FALSE(io::OutputDirectory::would_replace("ours", "ours-too/checkpoints.h5"));
  EXPECT_THROW(io::OutputDirectory("user"), std::runtime_error);
  fs::current_path(working);
  EXPECT_EQ(read(base / "user" / "data.txt"), "the user's");
  EXPECT_EQ(read(base / "file"), "the user's");
}
