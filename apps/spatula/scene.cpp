#include "scene.hpp"

#include "parameters/parameter_validation.hpp"

namespace spatula::app {

void OutputParameters::declare(Teuchos::ParameterList& output)
{
  const OutputParameters d;   // the defaults
  parameters::declare_string(output, "directory", d.directory,
                             "directory for all results, written as <directory>.partial and renamed at the end of the "
                             "run (<directory>.incomplete if it fails); never the working directory, one above it, or a "
                             "file or folder that spatula did not write");
  parameters::declare_bool(output, "overwrite", d.overwrite,
                           "replace an earlier result of spatula in 'directory' (false: refuse any existing directory)");
  parameters::declare_bool(output, "write mesh", d.write_mesh, "write the mesh as HDF5 + XDMF");
  parameters::declare_int(output, "field interval", d.field_interval,
                          "write displacement and I1 fields every this many converged steps (0: first and last)",
                          parameters::Range::closed(0, 100000));
  parameters::declare_bool(output, "convergence tables", d.convergence_tables,
                           "print the Newton iterations of every step");
  parameters::declare_double(output, "checkpoint interval", d.checkpoint_minutes,
                             "wall-clock minutes between checkpoints of the last converged state (checkpoints.h5, "
                             "'last state', with the state of a jump's energy descent under way), from which "
                             "'spatula scene.xml --resume' goes on after the run was killed "
                             "(0: only when the run stops on a signal or a failure)",
                             parameters::Range::closed(0.0, 1e6));
  parameters::declare_int(output, "tangent spectrum", d.tangent_spectrum,
                          "a diagnosis: at every converged state the tangent's eigenvalue nearest zero (this many "
                          "inverse iterations on its LDL^T factors, one factorization per state) and its mode's "
                          "participation ratio, into spectrum.csv (0: not computed)",
                          parameters::Range::closed(0, 100));
}

OutputParameters OutputParameters::from(const Teuchos::ParameterList& output)
{
  OutputParameters p;
  p.directory = output.get<std::string>("directory");
  p.overwrite = output.get<bool>("overwrite");
  p.write_mesh = output.get<bool>("write mesh");
  p.field_interval = output.get<int>("field interval");
  p.convergence_tables = output.get<bool>("convergence tables");
  p.checkpoint_minutes = output.get<double>("checkpoint interval");
  p.tangent_spectrum = output.get<int>("tangent spectrum");
  if (p.directory.empty()) throw parameters::InputError("parameter 'Output/directory' must not be empty");
  return p;
}

discretization::Enrichment enrichment_of(const Scene& scene)
{
  return scene.adhesion.enabled ? scene.adhesion.settings.enrichment : discretization::Enrichment::q1c1;
}

Teuchos::ParameterList valid_scene_parameters()
{
  Teuchos::ParameterList valid("spatula scene");
  geometry::ShapeParameters::declare(
      parameters::declare_sublist(valid, "Geometry", "the twelve spatula parameters of the paper's Table 2 [nm]"));
  mesh::MeshParameters::declare(parameters::declare_sublist(valid, "Mesh", "hexahedral mesh density"));
  OutputParameters::declare(parameters::declare_sublist(valid, "Output", "result files"));
  discretization::SolidParameters::declare(
      parameters::declare_sublist(valid, "Material", "Neo-Hookean solid and its quadrature"));
  LoadingParameters::declare(parameters::declare_sublist(valid, "Loading", "what the end face does"));
  solvers::LinearSolverParameters::declare(
      parameters::declare_sublist(valid, "Linear Solver", "solver of the Newton steps"));
  solvers::NewtonParameters::declare(parameters::declare_sublist(valid, "Nonlinear Solver", "Newton's method"));
  contact::AdhesionParameters::declare(
      parameters::declare_sublist(valid, "Adhesion", "van der Waals adhesion to a rigid substrate"));
  JobParameters::declare(parameters::declare_sublist(valid, "Job", "threads, and the end of a run after a signal"));
  return valid;
}

Scene read_scene(Teuchos::ParameterList user)
{
  parameters::validate(user, valid_scene_parameters());
  Scene scene;
  scene.geometry = geometry::ShapeParameters::from(user.sublist("Geometry"));
  scene.mesh = mesh::MeshParameters::from(user.sublist("Mesh"));
  scene.output = OutputParameters::from(user.sublist("Output"));
  scene.material = discretization::SolidParameters::from(user.sublist("Material"));
  scene.loading = LoadingParameters::from(user.sublist("Loading"));
  scene.linear_solver = solvers::LinearSolverParameters::from(user.sublist("Linear Solver"));
  scene.newton = solvers::NewtonParameters::from(user.sublist("Nonlinear Solver"));
  scene.job = JobParameters::from(user.sublist("Job"));
  scene.adhesion = contact::AdhesionParameters::from(user.sublist("Adhesion"), scene.material.young);
  // Laws that hold the pad along the substrate (the others leave a free X motion singular).
  const auto& law = scene.adhesion.settings.law;
  const bool tangential = scene.adhesion.model && scene.adhesion.model->holds_tangentially();
  if (scene.loading.free_slide && !tangential)
    throw parameters::InputError("parameter 'Loading/free slide during lift' = true needs 'Adhesion/law' = 'stiction' "
                                 "or 'adhesive friction' (got '" + law + "'): without tangential adhesion nothing "
                                 "holds the spatula in X and the system is singular");
  for (const auto& stage : scene.loading.stages) {
    const bool free_in_x = stage.free_slide || stage.kind == StageKind::slide_force;
    if (scene.loading.type == LoadingType::stages && free_in_x && !tangential)
      throw parameters::InputError("stage '" + stage.name + "' of 'Loading/Stages': " +
                                   (stage.free_slide ? "'free slide' = true" : "kind 'slide x force'") + " needs "
                                   "'Adhesion/law' = 'stiction' or 'adhesive friction' (got '" + law + "'): without "
                                   "tangential adhesion nothing holds the spatula in X and the system is singular");
  }
  // A law whose tangent is not symmetric (adhesive friction) has its Newton tangents factored LU.
  if (scene.adhesion.enabled && !scene.adhesion.model->symmetric())
    scene.linear_solver.mumps.symmetric = false;
  if (scene.adhesion.settings.anchor_at_restart) {
    if (scene.loading.restart_file.empty())
      throw parameters::InputError("parameter 'Adhesion/stiction anchors' = 'restart state' needs a state to restart "
                                   "from: 'Loading/restart file' is empty");
    if (!scene.loading.checkpoints.empty())
      throw parameters::InputError("parameter 'Adhesion/stiction anchors' = 'restart state' with 'Loading/checkpoints "
                                   "at theta_y': a restart from such a checkpoint would set the anchors at its state and "
                                   "measure the travel from another state");
  }
  scene.validated = user;
  return scene;
}

}  // namespace spatula::app
