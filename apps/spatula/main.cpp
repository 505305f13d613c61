// spatula: the gecko spatula adhesion program.
//
//   spatula [options] [scene.xml]        (command_line.cpp: the options)
//
// Without a file it runs the embedded default scene (xml/default.xml). Every input is validated before anything
// is computed or written; input errors name the key, the value and what is allowed (exit code 2).
#include "checkpoint.hpp"
#include "collective.hpp"
#include "command_line.hpp"
#include "default_scene.hpp"
#include "interruption.hpp"
#include "output_checks.hpp"
#include "preflight.hpp"
#include "resource_limits.hpp"
#include "scene.hpp"
#include "simulation.hpp"

#include "io/checked_write.hpp"
#include "io/hdf5_file.hpp"
#include "io/mesh_output.hpp"
#include "mesh/mesh_summary.hpp"
#include "io/output_directory.hpp"
#include "parameters/parameter_validation.hpp"
#include "mesh/partition.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_GlobalMPISession.hpp>
#include <Tpetra_Core.hpp>
#include <Teuchos_StandardCatchMacros.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace {

constexpr double pi = 3.14159265358979323846;

void write_summary_files(const spatula::io::OutputDirectory& directory, const spatula::mesh::MeshSummary& summary,
                         const spatula::geometry::SpatulaShape& shape, const std::string& mesh_choice)
{
  std::ostringstream text;
  spatula::mesh::print(text, summary);
  if (!mesh_choice.empty()) text << "  " << mesh_choice << "\n";
  text << "  r5 [nm]                             " << shape.r5() << "\n"
       << "  theta_s [deg]                       " << shape.theta_s() * 180.0 / pi << "\n";
  spatula::io::write_text_file(directory.file("mesh_summary.txt"), text.str());
  std::ostringstream csv;
  spatula::mesh::write_csv(csv, summary);
  csv << "r5_nm," << shape.r5() << "\ntheta_s_deg," << shape.theta_s() * 180.0 / pi << "\n";
  spatula::io::write_text_file(directory.file("mesh_summary.csv"), csv.str());
}

// A scene with everything checked that can be checked without solving, and its mesh.
struct Checked {
  std::optional<spatula::app::Scene> scene;
  std::optional<spatula::geometry::SpatulaShape> shape;
  spatula::mesh::HexMesh mesh;
  spatula::mesh::Partition partition;
  spatula::app::MemoryEstimate memory;
  std::string resume_from;   // --resume: the stopped run's directory
};

// Reads and checks the scene, the output directory, the mesh against the memory and the ranks, the restart file,
// the free space for the output: before anything is written, each check ending on every rank together (an
// InputError on all if one fails). A run (not --validate-only) then takes the output directory's lock (rank 0).
Checked check_everything(const spatula::app::CommandLine& options, const Teuchos::Comm<int>& comm, std::unique_ptr<spatula::io::RunLock>& lock)
{
  using namespace spatula;
  Checked run;
  app::agree(comm, [&] {
    const auto user = options.scene_file.empty()
                          ? parameters::read_xml_string(app::default_scene_xml, "the embedded default scene")
                          : parameters::read_xml_file(options.scene_file);
    run.scene = app::read_scene(user);
    run.shape.emplace(run.scene->geometry);
    if (options.resume) run.resume_from = app::prepare_resume(*run.scene);
    if (options.stop_after_checkpoint) app::set_stop_after_checkpoint(*run.scene, *options.stop_after_checkpoint);
  });
  app::agree(comm, [&] { app::check_output_directory(*run.scene, options.scene_file); }, true);
  app::agree(comm, [&] {
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: mesh"));
    run.mesh = app::make_mesh_within_memory(*run.scene, *run.shape, comm.getSize(), run.memory);
    run.partition = mesh::partition_mesh(run.mesh, comm.getSize());
    app::check_ranks(run.mesh, run.partition);
  });
  // 'auto' resolved from the memory estimate: rank 0's (each rank reads its own MemAvailable), so that every rank
  // builds the same solver.
  int solver = static_cast<int>(run.memory.solver);
  Teuchos::broadcast(comm, 0, &solver);
  run.memory.solver = static_cast<solvers::LinearSolverType>(solver);
  run.scene->linear_solver.type = run.memory.solver;
  app::agree(comm, [&] {
    if (run.scene->loading.restart_file.empty()) return;
    app::check_checkpoint(*run.scene,
                          discretization::make_node_space(run.mesh, run.partition, app::enrichment_of(*run.scene)));
  });
  app::agree(comm, [&] { app::check_output_limits(*run.scene, app::estimate_output(*run.scene, run.mesh)); }, true);
  if (!options.validate_only)
    app::agree(comm, [&] { lock = app::lock_output_directory(*run.scene, options.scene_file, run.resume_from); }, true);
  return run;
}

void print_summary(std::ostream& out, const Checked& run, const spatula::mesh::MeshSummary& summary)
{
  spatula::mesh::print(out, summary);
  if (!run.scene->mesh.choice.empty()) out << "  " << run.scene->mesh.choice << "\n";
  out << "  r5 [nm]                             " << run.shape->r5() << "\n"
      << "  theta_s [deg]                       " << run.shape->theta_s() * 180.0 / pi << "\n"
      << "  partition                           " << run.partition.ranks << " rank(s), elements per rank:";
  for (int r = 0; r < run.partition.ranks; ++r) out << " " << run.partition.elements_of(r).size();
  out << "\n  memory estimate                     " << run.memory.bytes / 1e9 << " GB";
  if (run.memory.available_source.empty()) out << " (no memory limit known)\n";
  else out << " of " << run.memory.available_bytes / 1e9 << " GB available (" << run.memory.available_source << ")\n";
  out << "  linear solver                       "
      << spatula::parameters::name_of(run.memory.solver, spatula::solvers::linear_solver_names())
      << (run.scene->validated.sublist("Linear Solver").get<std::string>("type") == "auto"
              ? " (chosen by 'Linear Solver/type' = auto: MUMPS while its factors fit in memory)" : "")
      << "\n";
}

// FAILURE.txt, as far as it can be written: where the disk is full, the error on the standard error says why.
void write_failure_text(const spatula::io::OutputDirectory& directory, const std::string& text)
{
  try {
    spatula::io::write_text_file(directory.file("FAILURE.txt"), text);
  } catch (const std::exception& error) {
    std::cerr << "spatula: " << error.what() << "\n";
    std::error_code ignored;
    std::filesystem::remove(directory.file("FAILURE.txt"), ignored);   // not a truncated note
  }
}

// What a stopped run leaves beside its partial results: why it stopped and how to go on.
void write_failure_note(const spatula::io::OutputDirectory& directory, const spatula::app::Stop& stop, int exit_code)
{
  std::ostringstream note;
  const auto& failure = stop.failure;
  note << "spatula stopped before the end of its load path (exit code " << exit_code << ").\n"
       << "why: " << failure.reason << "\n"
       << "where: step " << failure.step << ", stage '" << stop.stage << "', load " << failure.load
       << (stop.force ? (stop.moved == spatula::discretization::Master::lift ? " nN (P_z)" : " nN (P_x)")
           : stop.moved == spatula::discretization::Master::lift  ? " nm (u_z)"
           : stop.moved == spatula::discretization::Master::slide ? " nm (u_x)"
                                                                   : " (deg)");
  if (failure.smallest_increment > 0.0)
    note << ", not reached after cutting the increment to " << failure.smallest_increment;
  note << "\nresults up to the last converged state: curve.csv, mesh_states.xmf (this directory)\n";
  if (stop.checkpointed)
    note << "to go on from the last converged state in this directory (the curve and fields continued):\n"
         << "  spatula <the scene> --resume\n"
         << "to start another scene from that state instead, run it with\n"
         << "  Loading/restart file = '" << directory.incomplete_path() << "/checkpoints.h5'\n"
         << "  Loading/restart from = 'last state'\n"
         << "and another Output/directory (a run into '" << directory.final_path()
         << "' replaces this directory).\n";
  write_failure_text(directory, note.str());
}

// The run's field output: new, or a resumed run's own, kept up to the state it resumes from (if that cannot be
// read, a new one, said on `out`).
std::unique_ptr<spatula::io::XdmfOutput> open_fields(const spatula::io::OutputDirectory& directory, const Checked& run,
                                                     const spatula::app::Scene& scene, std::ostream& out)
{
  using spatula::io::XdmfOutput;
  if (scene.resume) {
    try {
      return std::make_unique<XdmfOutput>(directory.file(""), "mesh", run.mesh,
                                          spatula::app::read_run_record(scene).field_states,
                                          spatula::app::cell_field_names(scene), std::vector<std::string>{"displacement"});
    } catch (const std::exception& error) {
      out << "spatula: the stopped run's field states cannot be kept (" << error.what()
          << "): the fields start again at the resumed state\n";
    }
  }
  return std::make_unique<XdmfOutput>(directory.file(""), "mesh", run.mesh, run.partition);
}

// The output directory (new, or a stopped run's again with --resume), the validated scene and mesh summary in it,
// and the field output (rank 0).
void open_output(const Checked& run, const spatula::mesh::MeshSummary& summary,
                 std::unique_ptr<spatula::io::OutputDirectory>& directory,
                 std::unique_ptr<spatula::io::XdmfOutput>& fields, std::ostream& out)
{
  using namespace spatula;
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: output"));
  const auto& scene = *run.scene;
  if (scene.resume) {
    directory = std::make_unique<io::OutputDirectory>(scene.output.directory, run.resume_from);
    std::filesystem::remove(directory->file("FAILURE.txt"));
  } else {
    directory = std::make_unique<io::OutputDirectory>(scene.output.directory);
  }
  parameters::write_xml_file(scene.validated, directory->file("scene.xml"));
  write_summary_files(*directory, summary, *run.shape, run.scene->mesh.choice);
  if (scene.output.write_mesh || scene.loading.type != app::LoadingType::none)
    fields = open_fields(*directory, run, scene, out);
}

// What the watchdog leaves where a signal's stop does not reach a converged state in time (interruption.hpp).
void watch_output(const spatula::io::OutputDirectory& directory, const spatula::app::Scene& scene)
{
  std::ostringstream note;
  note << "spatula was ended by its watchdog: no converged state within 'Job/stop grace' = " << scene.job.stop_grace
       << " s of the signal to stop (exit code 128 + the signal).\n"
       << "results up to the last converged state: curve.csv (this directory)\n";
  spatula::app::set_watchdog_output(directory.file("FAILURE.txt"),
                                    spatula::io::OutputDirectory::staging_path(scene.output.directory),
                                    directory.incomplete_path(), note.str());
  if (scene.resume) spatula::app::note_checkpoint_written();   // the stopped run's checkpoint is there
}

// A run that stopped before the end of its load path: FAILURE.txt, the directory renamed <directory>.incomplete,
// and why on the standard error.
void leave_stopped_run(spatula::io::OutputDirectory& directory, const spatula::app::Stop& stop, int exit_code)
{
  write_failure_note(directory, stop, exit_code);
  directory.abandon();
  const char* what = stop.paused ? "stopped" : stop.signal ? "interrupted" : "solver failure";
  std::cerr << "spatula: " << what << " at step " << stop.failure.step << ", " << stop.stage << " = " << stop.failure.load << ": " << stop.failure.reason
            << "\nspatula: results up to the last converged state, a checkpoint to go on from and FAILURE.txt (how) "
            << "are in " << directory.incomplete_path() << "/\n";
}

}  // namespace

int main(int argc, char** argv)
{
  using namespace spatula;
  if (const auto why = app::limits_too_small_to_start(); !why.empty()) {   // (MPI's own failure would not say so)
    std::cerr << "spatula: input error: " << why << "\n";
    return 2;
  }
  Teuchos::GlobalMPISession mpi_session(&argc, &argv, nullptr);
  const app::CommandLine options = app::parse_command_line(argc, argv);
  app::KokkosArguments kokkos_arguments(options.kokkos_arguments);   // Kokkos sees its own options only
  Tpetra::ScopeGuard kokkos_scope(&kokkos_arguments.argc, &kokkos_arguments.argv);   // (not lazily at the first Map)
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const bool root = comm->getRank() == 0;
  std::ostream& out = std::cout;
  app::install_interruption_handlers();
  std::unique_ptr<io::RunLock> lock;                // rank 0: held until the output directory's last rename
  std::unique_ptr<io::OutputDirectory> directory;   // rank 0, once the run has started
  std::unique_ptr<io::XdmfOutput> fields;
  // A failure after the output directory exists, possibly on some ranks only while the others wait in a collective
  // call: partial results and FAILURE.txt in <directory>.incomplete, and the whole job ends with exit code 1.
  auto failed_after_start = [&](const std::exception& error) {
    std::cerr << "spatula: error (rank " << comm->getRank() << "): " << error.what() << "\n";
    if (directory) {
      fields.reset();
      write_failure_text(*directory, "spatula stopped with an error (exit code 1): " + std::string(error.what()) + "\n");
      try {
        directory->abandon();
      } catch (const std::exception& rename_error) {   // (the directory was removed under the run, say)
        std::cerr << "spatula: " << rename_error.what() << "\n";
      }
      std::cerr << "spatula: partial results in " << directory->incomplete_path() << "/\n";
    }
    lock.reset();   // the directory's last rename is done
    if (comm->getSize() > 1) app::abort_all(1);
    if (io::Hdf5File::unclosed_files()) app::end_now(1);
    return 1;
  };

  try {
    if (!options.error.empty()) throw parameters::InputError(options.error + "\n" + app::usage());
    if (options.help || options.version || options.kokkos_help) {   // (Kokkos has printed its help)
      if (root && options.help) out << app::usage();
      if (root && options.version) out << app::version_text();
      return 0;
    }
    if (options.print_parameters) {
      if (root) app::valid_scene_parameters().print(out, Teuchos::ParameterList::PrintOptions().showDoc(true).indent(2).showTypes(true));
      return 0;
    }
    Checked run = check_everything(options, *comm, lock);
    app::set_stop_grace(run.scene->job.stop_grace);
    const std::string threads = app::set_threads(run.scene->job);
    const auto summary = mesh::summarize(run.mesh, run.scene->mesh.level);
    if (root) print_summary(out, run, summary);
    if (root) out << "  " << threads << "\n";
    if (options.validate_only) {
      if (root) out << "spatula: scene " << (options.scene_file.empty() ? "<default>" : options.scene_file) << " is valid\n";
      return 0;
    }

    auto& scene = *run.scene;
    if (scene.resume) scene.loading.restart_file = app::resumed_checkpoint_file(scene);
    app::agree(*comm, [&] { open_output(run, summary, directory, fields, out); }, true);
    if (root) watch_output(*directory, scene);
    if (root && scene.resume) out << "spatula: resuming the stopped run " << run.resume_from << std::endl;   // (tests wait for it)
    if (scene.loading.type != app::LoadingType::none) {
      const auto stop =
          app::run_simulation(scene, *run.shape, run.mesh, run.partition, comm, directory.get(), fields.get(), out);
      if (stop) {
        const int exit_code = stop->paused ? 0 : stop->signal ? 128 + stop->signal : 1;
        if (root) {
          fields.reset();
          leave_stopped_run(*directory, *stop, exit_code);
        }
        return exit_code;
      }
    }
    if (root) {
      fields.reset();
      directory->commit();
      out << "spatula: results in " << scene.output.directory << "/\n";
    }
    Teuchos::TimeMonitor::summarize(comm.ptr(), out, false, true, false, Teuchos::Union, "spatula:");
  } catch (const parameters::InputError& error) {
    if (directory) return failed_after_start(error);
    if (root) std::cerr << "spatula: input error: " << error.what() << "\n";   // agreed by every rank, nothing written
    return 2;
  } catch (const app::AgreedFailure& error) {
    if (root) std::cerr << "spatula: error: " << error.what() << "\n";
    if (root && directory) directory->abandon();
    return 1;
  } catch (const std::bad_alloc& error) {   // one rank's allocation (solvers/out_of_memory.hpp, allocation.cpp)
    const std::string what = error.what();
    return failed_after_start(std::runtime_error(what.rfind("out of memory", 0) == 0 ? what : "out of memory: " + what));
  } catch (const std::exception& error) {
    return failed_after_start(error);
  }
  return 0;
}
