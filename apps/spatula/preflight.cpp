#include "preflight.hpp"

#include "checkpoint.hpp"
#include "analysis/instability_policy.hpp"
#include "resource_limits.hpp"
#include "mesh/mesh_summary.hpp"
#include "io/output_directory.hpp"
#include "parameters/parameter_validation.hpp"
#include "mesh/spatula_mesher.hpp"

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

namespace spatula::app {

namespace {

std::string gigabytes(double bytes)
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(bytes < 1e10 ? 2 : 0) << bytes / 1e9 << " GB";
  return out.str();
}

// Peak memory for n unknowns. Matrix: ~81 entries per row (27 neighbouring nodes x 3), held by Tpetra (values and
// indices, owned and overlapping rows) and copied once by the solver: about 2.5 x 12 bytes per entry. Direct solver
// (MUMPS LDL^T): the fine mesh's measured 3.5 GB at 318,087 unknowns, grown as n^(4/3). ILU(k): k + 2 matrices.
// Algebraic multigrid: the fine mesh's measured 2.2 GB (both ranks' peak resident memory in the solid benchmark,
// against 3.8 GB with MUMPS in the same benchmark: the two models come from different runs), grown as n.
struct MemoryModel {
  static constexpr double entries_per_unknown = 81.0, bytes_per_entry = 30.0;
  static constexpr double measured_unknowns = 318087.0, measured_bytes = 3.5e9, measured_multigrid_bytes = 2.2e9;
  static double direct(double unknowns) { return measured_bytes * std::pow(unknowns / measured_unknowns, 4.0 / 3.0); }
  static double multigrid(double unknowns) { return measured_multigrid_bytes * unknowns / measured_unknowns; }
  static double iterative(double unknowns, int fill)
  {
    return (fill + 2) * entries_per_unknown * bytes_per_entry * unknowns;
  }
};

constexpr double usable_memory = 0.9;   // of the tightest memory limit

// A scene that jumps past instabilities factors the tangent with MUMPS LDL^T at every jump (the descent needs its
// inertia) whatever the linear solver: an iterative solver then saves no peak memory.
double solver_bytes(solvers::LinearSolverType type, const Scene& scene, double unknowns)
{
  const double jumps = instability_policy(scene.loading)->jumps()
                           ? MemoryModel::direct(unknowns) : 0.0;
  switch (type) {
    case solvers::LinearSolverType::gmres_ilu:
      return std::max(jumps, MemoryModel::iterative(unknowns, scene.linear_solver.fill_level));
    case solvers::LinearSolverType::gmres_amg: return std::max(jumps, MemoryModel::multigrid(unknowns));
    default: return MemoryModel::direct(unknowns);
  }
}

// The solver 'auto' picks: MUMPS while its factors fit in memory (it was the faster at every size measured here:
// docs/solvers.md), else the algebraic multigrid (which fits only where no jump needs the factors).
solvers::LinearSolverType chosen_solver(const Scene& scene, double unknowns, double available_bytes)
{
  if (scene.linear_solver.type != solvers::LinearSolverType::automatic) return scene.linear_solver.type;
  const bool direct_fits = MemoryModel::direct(unknowns) <= usable_memory * available_bytes;
  return direct_fits ? solvers::LinearSolverType::mumps : solvers::LinearSolverType::gmres_amg;
}

double peak_bytes(const Scene& scene, double unknowns, double available_bytes)
{
  return solver_bytes(chosen_solver(scene, unknowns, available_bytes), scene, unknowns);
}

// A geometry parameter as a message names it.
struct GeometryParameter {
  const char* name;
  double geometry::ShapeParameters::*value;
};

// The geometry parameters that shape each part of the mesh (paper Fig. 2).
std::vector<GeometryParameter> part_parameters(mesh::Part part)
{
  using P = geometry::ShapeParameters;
  const GeometryParameter a_s{"a_s", &P::a_s}, b_s{"b_s", &P::b_s}, c_s{"c_s", &P::c_s}, l_s{"l_s", &P::l_s},
      l_p{"l_p", &P::l_p}, h_p{"h_p", &P::h_p}, h_r{"h_r", &P::h_r}, w_p{"w_p", &P::w_p}, r1{"r1", &P::r1},
      r2{"r2", &P::r2}, r3{"r3", &P::r3}, r4{"r4", &P::r4};
  switch (part) {
    case mesh::Part::shaft_and_rim: return {a_s, b_s, c_s, l_s, l_p, h_r, w_p, r1, r3};
    case mesh::Part::outer_pad: return {l_p, w_p, h_r, h_p, r1, r2, r3, r4};
    case mesh::Part::prism: return {l_p, h_r, h_p, r3, r4};
    case mesh::Part::thin_pad: return {l_p, w_p, h_p, r2, r4};
  }
  return {};
}

// Whether a geometry can be meshed into usable elements (at the scene's mesh level).
bool meshes_well(const geometry::ShapeParameters& parameters, const mesh::MeshParameters& density)
{
  try {
    const geometry::SpatulaShape shape(parameters);
    return !mesh::find_defective_element(mesh::mesh_spatula(shape, density));
  } catch (const std::exception&) {
    return false;
  }
}

// For each parameter of the part that the scene moved from its default: where between the scene's value and the
// default the mesh becomes usable, the others as given (bisection, 12 halvings). "l_p >= about 171 (default 350)".
std::string usable_ranges(const Scene& scene, mesh::Part part)
{
  const geometry::ShapeParameters defaults;
  auto density = scene.mesh;
  density.refinement_factor = 1;
  std::ostringstream ranges;
  for (const auto& parameter : part_parameters(part)) {
    const double given = scene.geometry.*(parameter.value), preset = defaults.*(parameter.value);
    if (given == preset) continue;
    auto trial = scene.geometry;
    trial.*(parameter.value) = preset;
    if (!meshes_well(trial, density)) continue;   // moving this one alone does not help
    double bad = given, good = preset;
    for (int halving = 0; halving < 12; ++halving) {
      trial.*(parameter.value) = 0.5 * (bad + good);
      (meshes_well(trial, density) ? good : bad) = 0.5 * (bad + good);
    }
    ranges << (ranges.tellp() > 0 ? "; " : "") << "'Geometry/" << parameter.name << "' = " << given
           << (given < preset ? " is too small: usable from about " : " is too large: usable up to about ")
           << std::setprecision(4) << good << " (default " << preset << ")";
  }
  return ranges.str();
}

// The message for a geometry whose parts do not fit together at `part`.
[[noreturn]] void geometry_does_not_fit(const Scene& scene, mesh::Part part, const std::string& what)
{
  std::ostringstream message;
  message << "the geometry's parts do not fit together in " << mesh::part_name(part) << ": " << what
          << ". The parameters that shape this part:";
  for (const auto& parameter : part_parameters(part)) message << " 'Geometry/" << parameter.name << "'";
  const std::string ranges = usable_ranges(scene, part);
  message << (ranges.empty() ? " (move them towards the paper's Table 2 values)" : ". With the others as given: " + ranges);
  throw parameters::InputError(message.str());
}

// A part of a scene as --resume compares it. A jump's iteration limit may differ (a descent stopped at it goes on with
// a larger one), and so may its descent method (either ends on the same stable state; a run stopped before 'auto'
// was the default wrote 'shifted newton').
Teuchos::ParameterList resumable_part(Teuchos::ParameterList& scene, const std::string& part)
{
  Teuchos::ParameterList list = scene.sublist(part);
  if (part == "Loading" && list.isSublist("Jump"))
    for (const char* setting : {"maximum iterations", "method", "trust region from"})
      list.sublist("Jump").remove(setting, false);
  return list;
}

}  // namespace

std::string prepare_resume(Scene& scene)
{
  const std::string key = "--resume with 'Output/directory' = '" + parameters::shorten(scene.output.directory) + "'";
  const auto stopped_runs = io::OutputDirectory::stopped_runs(scene.output.directory);
  for (const auto& stopped : stopped_runs) {
    const std::string file = (std::filesystem::path(stopped) / "checkpoints.h5").string();
    if (!resumable(file)) continue;
    if (scene.adhesion.settings.anchor_at_restart && !holds_anchors(file))
      throw parameters::InputError(key + ": 'Adhesion/stiction anchors' = 'restart state', but the last state in '" +
                                   stopped + "' does not hold the anchors' state (a run stopped by a version before "
                                   "they were checkpointed): run the scene again from its start");
    auto earlier = parameters::read_xml_file((std::filesystem::path(stopped) / "scene.xml").string());
    // A run stopped by an earlier version of the program lacks the parameters added since: they take their
    // defaults, as for any scene (a parameter is added with the default that keeps the behaviour before it). A
    // list this version does not accept is left as written, and the comparison below reports the difference.
    try {
      parameters::validate(earlier, valid_scene_parameters());
    } catch (const parameters::InputError&) {
    }
    for (const char* part : {"Geometry", "Mesh", "Material", "Adhesion", "Loading"})   // values, in any order
      if (!earlier.isSublist(part) ||
          !Teuchos::haveSameValuesSorted(resumable_part(earlier, part), resumable_part(scene.validated, part)))
        throw parameters::InputError(key + ": the stopped run in '" + stopped + "' was made with other '" + part +
                                     "' parameters (its scene.xml): resume it with its own scene, or run this one "
                                     "without --resume (which replaces it)");
    scene.resume = true;
    scene.loading.restart_file = file;
    scene.loading.restart_from_last_state = true;
    return stopped;
  }
  throw parameters::InputError(key + ": no stopped run to go on from (" +
                               (stopped_runs.empty() ? std::string("no <directory>.partial or .incomplete")
                                                     : "no 'last state' checkpoint in " + stopped_runs.front()) +
                               "); run the scene without --resume");
}

void set_stop_after_checkpoint(Scene& scene, double theta_y)
{
  const auto& loading = scene.loading;
  std::ostringstream key;
  key << "--stop-after-checkpoint " << theta_y;
  const bool rotates = std::any_of(loading.stages.begin(), loading.stages.end(),
                                   [](const Stage& s) { return s.kind == StageKind::rotate && s.checkpoints; });
  const bool listed = std::any_of(loading.checkpoints.begin(), loading.checkpoints.end(),
                                  [&](double c) { return checkpoint_label(c) == checkpoint_label(theta_y); });
  if (!rotates || !listed) {
    std::ostringstream allowed;
    for (double c : loading.checkpoints) allowed << (allowed.tellp() > 0 ? ", " : "") << c;
    throw parameters::InputError(
        key.str() + ": " +
        (!rotates ? std::string("the scene has no rotation that writes checkpoints")
         : loading.checkpoints.empty() ? std::string("the scene's 'Loading/checkpoints at theta_y' is empty")
                                       : "not one of the scene's 'Loading/checkpoints at theta_y' = " + allowed.str()) +
        " (the inclinations [deg] where the rotation stops to write a checkpoint)");
  }
  if (scene.resume && holds_checkpoint(loading.restart_file, checkpoint_label(theta_y)))
    throw parameters::InputError(key.str() + " with --resume: the stopped run has passed that inclination already (" +
                                 loading.restart_file + " holds its checkpoint '" + checkpoint_label(theta_y) +
                                 "'): take the checkpoint from there, or resume without the option");
  scene.stop_after_checkpoint = theta_y;
}

std::string resumed_checkpoint_file(const Scene& scene)
{
  return (std::filesystem::path(io::OutputDirectory::staging_path(scene.output.directory)) / "checkpoints.h5").string();
}

void check_output_directory(const Scene& scene, const std::string& scene_file)
{
  const auto& directory = scene.output.directory;
  const std::string key = "parameter 'Output/directory' = '" + parameters::shorten(directory) + "'";
  if (const auto why = io::OutputDirectory::refusal(directory, scene.output.overwrite))
    throw parameters::InputError(key + " cannot be used: " + *why);
  if (!scene_file.empty() && io::OutputDirectory::would_replace(directory, scene_file))
    throw parameters::InputError(key + " would replace the scene file '" + scene_file +
                                 "' itself: copy the scene elsewhere or choose another directory");
  if (!scene.resume && !scene.loading.restart_file.empty() && io::OutputDirectory::would_replace(directory, scene.loading.restart_file))
    throw parameters::InputError(key + " would replace 'Loading/restart file' = '" + scene.loading.restart_file +
                                 "' before the run could finish: choose another 'Output/directory'");
}

MemoryEstimate estimate_memory(const Scene& scene, std::int64_t unrefined_nodes, std::int64_t refined_nodes, int ranks)
{
  // nodes(r) = a + b r^2 through r = 1 and 2 (the pad refines in plane, the shaft does not).
  MemoryEstimate estimate;
  estimate.refined_nodes = (refined_nodes - unrefined_nodes) / 3.0;
  estimate.fixed_nodes = unrefined_nodes - estimate.refined_nodes;
  estimate.nodes = static_cast<std::int64_t>(estimate.nodes_at(scene.mesh.refinement_factor));
  estimate.unknowns = 3 * estimate.nodes;
  estimate.matrix_entries = static_cast<std::int64_t>(MemoryModel::entries_per_unknown * estimate.unknowns);
  const auto limit = tightest(memory_limits(ranks));
  estimate.available_bytes = limit.bytes;
  estimate.available_source = limit.source;
  estimate.available_remedy = limit.remedy;
  estimate.solver = chosen_solver(scene, double(estimate.unknowns), estimate.available_bytes);
  estimate.bytes = solver_bytes(estimate.solver, scene, double(estimate.unknowns));
  return estimate;
}

void check_memory(const Scene& scene, const MemoryEstimate& estimate)
{
  if (estimate.bytes <= usable_memory * estimate.available_bytes) return;   // (an unknown limit is infinite)
  const auto& m = scene.mesh;
  std::ostringstream message;
  message << "the mesh ('Mesh/level' = '" << m.level << "', 'Mesh/refinement factor' = " << m.refinement_factor
          << ", 'Mesh/layers' = " << m.layers << ") has about " << estimate.unknowns << " unknowns and needs about "
          << gigabytes(estimate.bytes) << " with 'Linear Solver/type' = '"
          << parameters::name_of(estimate.solver, solvers::linear_solver_names()) << "'; "
          << gigabytes(estimate.available_bytes) << " available (" << estimate.available_source << "). ";
  if (estimate.available_bytes <= 0.0)   // the libraries alone fill the limit: no mesh fits
    throw parameters::InputError(message.str() + "Nothing is left for any mesh under this limit: " +
                                 estimate.available_remedy);
  int fits = 0;
  for (int r = 1; r < m.refinement_factor; ++r)
    if (peak_bytes(scene, 3.0 * estimate.nodes_at(r), estimate.available_bytes) <= usable_memory * estimate.available_bytes)
      fits = r;
  if (fits > 0) message << "Allowed here: 'Mesh/refinement factor' <= " << fits << "";
  else if (!m.choice.empty()) message << "Raise 'Mesh/target error' (with 'Mesh/level' = auto) for a coarser mesh";
  else message << "Use a coarser 'Mesh/level' or fewer 'Mesh/layers'";
  if (estimate.solver == solvers::LinearSolverType::mumps) {
    const double multigrid =
        solver_bytes(solvers::LinearSolverType::gmres_amg, scene, double(estimate.unknowns));
    message << ", or the iterative solver 'Linear Solver/type' = 'gmres-amg' (about " << gigabytes(multigrid)
            << (multigrid <= usable_memory * estimate.available_bytes ? ", fits" : ", does not fit either")
            << (instability_policy(scene.loading)->jumps()
                    ? ": the jumps past instabilities factor with MUMPS all the same" : "") << ")";
  }
  message << "; or " << estimate.available_remedy;
  throw parameters::InputError(message.str());
}

mesh::HexMesh make_checked_mesh(const Scene& scene, const geometry::SpatulaShape& shape)
{
  mesh::HexMesh mesh;
  try {
    mesh = mesh::mesh_spatula(shape, scene.mesh);
  } catch (const mesh::MeshingError& error) {
    geometry_does_not_fit(scene, error.part, error.what());
  }
  if (const auto defect = mesh::find_defective_element(mesh)) {
    std::ostringstream what;
    what << defect->defective_elements << " inverted or degenerate element(s) at 'Mesh/level' = '" << scene.mesh.level
         << "', the worst element " << defect->element << " (det J at a Gauss point " << defect->gauss_jacobian
         << " nm^3, scaled Jacobian " << defect->scaled_jacobian << ", usable from " << mesh::smallest_scaled_jacobian
         << ")";
    geometry_does_not_fit(scene, defect->part, what.str());
  }
  return mesh;
}

mesh::HexMesh make_mesh_within_memory(const Scene& scene, const geometry::SpatulaShape& shape, int ranks,
                                      MemoryEstimate& estimate)
{
  auto trial = scene;
  const int requested = scene.mesh.refinement_factor;
  trial.mesh.refinement_factor = 1;
  auto mesh = make_checked_mesh(trial, shape);
  const std::int64_t unrefined_nodes = mesh.node_count();
  if (requested > 1) {
    trial.mesh.refinement_factor = 2;
    mesh = make_checked_mesh(trial, shape);
  }
  estimate = estimate_memory(scene, unrefined_nodes, requested > 1 ? mesh.node_count() : 4 * unrefined_nodes, ranks);
  check_memory(scene, estimate);
  return requested > 2 ? make_checked_mesh(scene, shape) : mesh;
}

void check_ranks(const mesh::HexMesh& mesh, const mesh::Partition& partition)
{
  for (int rank = 0; rank < partition.ranks; ++rank)
    if (partition.elements_of(rank).empty())
      throw parameters::InputError("MPI: " + std::to_string(partition.ranks) + " ranks for a mesh of " +
                                   std::to_string(mesh.element_count()) + " elements leave rank " +
                                   std::to_string(rank) + " without elements: run on fewer ranks");
}

}  // namespace spatula::app
