#include "output_checks.hpp"

#include "preflight.hpp"
#include "resource_limits.hpp"

#include "io/output_directory.hpp"
#include "parameters/parameter_validation.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include <sys/statvfs.h>

namespace spatula::app {

namespace {

namespace fs = std::filesystem;

std::string key_of(const Scene& scene)
{
  return "parameter 'Output/directory' = '" + parameters::shorten(scene.output.directory) + "'";
}

std::string megabytes(double bytes)
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(bytes < 1e7 ? 2 : 0) << bytes / 1e6 << " MB";
  return out.str();
}

// Converged states of a stage of `range` in increments that start at `steps.initial`: one and a half times the
// count at that increment (cuts near instabilities), at least 10. (The default scene: 135 estimated, 102 taken.)
double states_over(double range, const analysis::StepParameters& steps)
{
  const double increment = std::max(steps.minimum, std::min(steps.initial, steps.maximum));
  return std::max(10.0, 1.5 * std::abs(range) / increment);
}

// The nearest existing ancestor of a path (the file system the output goes to).
fs::path existing_ancestor(const fs::path& path)
{
  std::error_code error;
  fs::path ancestor = fs::absolute(path).lexically_normal();
  while (!ancestor.empty() && !fs::exists(ancestor, error) && ancestor != ancestor.parent_path())
    ancestor = ancestor.parent_path();
  return ancestor;
}

}  // namespace

std::unique_ptr<io::RunLock> lock_output_directory(const Scene& scene, const std::string& scene_file,
                                                   const std::string& resume_from)
{
  fs::path directory = fs::absolute(scene.output.directory).lexically_normal();
  if (directory.filename().empty() && directory.has_parent_path()) directory = directory.parent_path();   // "out/"
  const fs::path parent = directory.parent_path();
  std::error_code error;
  fs::create_directories(parent, error);
  if (error)
    throw parameters::InputError(key_of(scene) + ": cannot create its parent directory '" + parent.string() +
                                 "': " + error.message());
  std::unique_ptr<io::RunLock> lock;
  try {
    lock = std::make_unique<io::RunLock>(scene.output.directory);
  } catch (const io::DirectoryInUse& in_use) {
    throw parameters::InputError(key_of(scene) + " cannot be used: " + in_use.what());
  } catch (const std::exception& failure) {
    throw parameters::InputError(key_of(scene) + " cannot be used: " + failure.what());
  }
  check_output_directory(scene, scene_file);   // again, now that no other run can change it
  if (!resume_from.empty() && !io::OutputDirectory::is_ours(resume_from))
    throw parameters::InputError("--resume with " + key_of(scene) + ": the stopped run '" + resume_from +
                                 "' was taken over by another run meanwhile: run the scene again (with --resume if "
                                 "that run stopped too)");
  return lock;
}

OutputEstimate estimate_output(const Scene& scene, const mesh::HexMesh& mesh)
{
  const double nodes = double(mesh.node_count()), elements = double(mesh.element_count());
  const auto& loading = scene.loading;
  double states = 1.0;   // the rotation's range from the undeformed state for the fixed types (as they were estimated)
  if (loading.type == LoadingType::rotation) states = states_over(loading.theta_y, loading.rotation_steps);
  if (loading.type == LoadingType::lift) states = states_over(loading.final_lift, loading.lift_steps);
  if (loading.type == LoadingType::stages)
    for (const auto& stage : loading.stages) states += states_over(stage.target, stage.steps);
  // HDF5 and XDMF: the mesh (coordinates, connectivity, parts, node and side sets) and per field state the deformed
  // coordinates, the displacement and up to one more node vector and two cell scalars, each dataset with a few kB
  // of metadata; the XDMF text per state.
  constexpr double per_dataset = 2048.0, xdmf_per_state = 1024.0;
  const double mesh_bytes = nodes * (3 * 8 + 2 * 8) + elements * (8 * 8 + 2 * 4) + 24 * per_dataset;
  const double state_bytes = nodes * 9 * 8 + elements * 2 * 8 + 6 * per_dataset + xdmf_per_state;
  const double field_states =
      scene.output.field_interval > 0 ? 2.0 + states / scene.output.field_interval : 2.0;
  const bool fields = scene.output.write_mesh || loading.type != LoadingType::none;
  // A checkpoint: the state with its enrichment and the stiction anchors (within 2 x 3 values per node), a contact
  // law's histories (per contact face and quadrature point; a quadrilateral surface has fewer faces than nodes), and
  // the file twice while it is replaced.
  double history_bytes = 0.0;
  if (scene.adhesion.enabled) {
    const auto& contact = scene.adhesion.model;
    const double order = contact->quadrature_order(), surface_nodes = mesh.nodes(mesh::Boundary::contact).size();
    history_bytes = surface_nodes * order * order * contact->history_size() * 8;
  }
  const double checkpoint_bytes = nodes * 6 * 8 + history_bytes + 10 * per_dataset;
  const double checkpoints = loading.type == LoadingType::none ? 0.0 : 2.0 * (double(loading.checkpoints.size()) + 1.0);
  constexpr double curve_row = 400.0, small_files = 64.0 * 1024.0;   // scene, summaries, FAILURE.txt, marker
  OutputEstimate estimate;
  const double fields_file = fields ? mesh_bytes + field_states * state_bytes : 0.0;
  const double checkpoints_file = 0.5 * checkpoints * checkpoint_bytes;   // (the other half: the copy replaced)
  estimate.total = fields_file + checkpoints * checkpoint_bytes + states * curve_row + small_files;
  estimate.largest = std::max({fields_file, checkpoints_file, states * curve_row});
  estimate.largest_file = estimate.largest == fields_file ? "mesh.h5"
                          : estimate.largest == checkpoints_file ? "checkpoints.h5" : "curve.csv";
  return estimate;
}

void check_output_limits(const Scene& scene, const OutputEstimate& estimate)
{
  const auto file_size = file_size_limit();
  if (estimate.largest > file_size.value)
    throw parameters::InputError(key_of(scene) + ": the run will write a file of up to about " +
                                 megabytes(estimate.largest) + " (" + estimate.largest_file + "), above " +
                                 file_size.name + " of " + megabytes(file_size.value) + ": raise the limit (ulimit -f "
                                 "unlimited) or write fewer field states ('Output/field interval')");
  const double output_bytes = estimate.total;
  const fs::path ancestor = existing_ancestor(scene.output.directory);
  struct statvfs space {};
  if (::statvfs(ancestor.c_str(), &space) != 0) return;   // unknown: the writes themselves are checked
  const double free_bytes = double(space.f_bavail) * double(space.f_frsize);
  if (output_bytes > free_bytes)
    throw parameters::InputError(key_of(scene) + ": the run will write up to about " + megabytes(output_bytes) +
                                 " (mesh, field states every 'Output/field interval' steps, checkpoints, curve), but "
                                 "the file system of '" + ancestor.string() + "' has " + megabytes(free_bytes) +
                                 " free: free some space, choose another directory, or write fewer field states");
}

}  // namespace spatula::app
