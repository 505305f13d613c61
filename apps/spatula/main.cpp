// spatula: the gecko spatula adhesion program.
//
//   spatula [scene.xml] [--validate-only] [--print-parameters]
//
// Without a file it runs the embedded default scene (xml/default.xml). Every input is validated before anything
// is computed or written; input errors name the key, the value and what is allowed (exit code 2).
#include "default_scene.hpp"
#include "scene.hpp"
#include "simulation.hpp"

#include "mesh_output.hpp"
#include "mesh_summary.hpp"
#include "output_directory.hpp"
#include "parameter_validation.hpp"
#include "partition.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_StandardCatchMacros.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <fstream>
#include <iostream>

namespace {

constexpr double pi = 3.14159265358979323846;

struct Options {
  std::string scene_file;
  bool validate_only = false;
  bool print_parameters = false;
};

const char* usage =
    "usage: spatula [scene.xml] [--validate-only] [--print-parameters]\n"
    "  scene.xml           Teuchos XML parameter list (default: the embedded scene xml/default.xml)\n"
    "  --validate-only     check the scene and exit\n"
    "  --print-parameters  print every valid key with its default and documentation\n";

Options parse(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--validate-only") options.validate_only = true;
    else if (argument == "--print-parameters") options.print_parameters = true;
    else if (argument == "--help" || argument == "-h") {
      std::cout << usage;
      std::exit(0);
    } else if (!argument.empty() && argument[0] == '-')
      throw spatula::parameters::InputError("unknown option '" + argument + "'\n" + usage);
    else if (options.scene_file.empty()) options.scene_file = argument;
    else throw spatula::parameters::InputError("more than one scene file given ('" + options.scene_file + "', '" +
                                               argument + "')\n" + usage);
  }
  return options;
}

void write_summary_files(const spatula::io::OutputDirectory& directory, const spatula::mesh::MeshSummary& summary,
                         const spatula::geometry::SpatulaShape& shape)
{
  std::ofstream text(directory.file("mesh_summary.txt"));
  spatula::mesh::print(text, summary);
  text << "  r5 [nm]                             " << shape.r5() << "\n"
       << "  theta_s [deg]                       " << shape.theta_s() * 180.0 / pi << "\n";
  std::ofstream csv(directory.file("mesh_summary.csv"));
  spatula::mesh::write_csv(csv, summary);
  csv << "r5_nm," << shape.r5() << "\ntheta_s_deg," << shape.theta_s() * 180.0 / pi << "\n";
}

}  // namespace

int main(int argc, char** argv)
{
  using namespace spatula;
  Teuchos::GlobalMPISession mpi_session(&argc, &argv, nullptr);
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const bool root = comm->getRank() == 0;
  std::ostream& out = std::cout;

  try {
    const Options options = parse(argc, argv);
    if (options.print_parameters) {
      if (root) app::valid_scene_parameters().print(out, Teuchos::ParameterList::PrintOptions().showDoc(true).indent(2).showTypes(true));
      return 0;
    }
    const auto user = options.scene_file.empty()
                          ? parameters::read_xml_string(app::default_scene_xml, "the embedded default scene")
                          : parameters::read_xml_file(options.scene_file);
    const app::Scene scene = app::read_scene(user);
    const geometry::SpatulaShape shape(scene.geometry);
    if (options.validate_only) {
      if (root) out << "spatula: scene " << (options.scene_file.empty() ? "<default>" : options.scene_file) << " is valid\n";
      return 0;
    }

    mesh::HexMesh mesh;
    mesh::Partition partition;
    {
      Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: mesh"));
      mesh = mesh::mesh_spatula(shape, scene.mesh);
      partition = mesh::partition_mesh(mesh, comm->getSize());
    }
    const auto summary = mesh::summarize(mesh, scene.mesh.level);
    std::unique_ptr<io::OutputDirectory> directory;
    std::unique_ptr<io::XdmfOutput> fields;
    if (root) {
      mesh::print(out, summary);
      out << "  r5 [nm]                             " << shape.r5() << "\n"
          << "  theta_s [deg]                       " << shape.theta_s() * 180.0 / pi << "\n"
          << "  partition                           " << partition.ranks << " rank(s), elements per rank:";
      for (int r = 0; r < partition.ranks; ++r) out << " " << partition.elements_of(r).size();
      out << "\n";
      Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: output"));
      directory = std::make_unique<io::OutputDirectory>(scene.output.directory);
      parameters::write_xml_file(scene.validated, directory->file("scene.xml"));
      write_summary_files(*directory, summary, shape);
      if (scene.output.write_mesh || scene.loading.type != "none")
        fields = std::make_unique<io::XdmfOutput>(directory->file(""), "mesh", mesh, partition);
    }
    if (scene.loading.type != "none") {
      const auto failure =
          app::run_simulation(scene, shape, mesh, partition, comm, directory.get(), fields.get(), out);
      if (failure) {
        if (root) {
          std::ofstream(directory->file("FAILURE.txt"))
              << "step " << failure->step << ": load " << failure->load << " not reached (smallest increment "
              << failure->smallest_increment << "): " << failure->reason << "\n";
          directory->abandon();
          std::cerr << "spatula: solver failure at step " << failure->step << ", load " << failure->load
                    << " (rotation theta_y - theta_s in deg, or lift in nm) after cutting the increment to " << failure->smallest_increment << ": "
                    << failure->reason << "\nspatula: results up to the last converged step are in "
                    << scene.output.directory << ".incomplete/\n";
        }
        return 3;
      }
    }
    if (root) {
      directory->commit();
      out << "spatula: results in " << scene.output.directory << "/\n";
    }
    Teuchos::TimeMonitor::summarize(comm.ptr(), out, false, true, false, Teuchos::Union, "spatula:");
  } catch (const parameters::InputError& error) {
    if (root) std::cerr << "spatula: input error: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "spatula: error (rank " << comm->getRank() << "): " << error.what() << "\n";
    return 1;
  }
  return 0;
}
