#pragma once
// A scene: the whole XML input of one run, validated against the parameters every package declares.
#include "contact/adhesion.hpp"
#include "discretization/discrete_system.hpp"
#include "job.hpp"
#include "loading.hpp"
#include "solvers/newton.hpp"
#include "mesh/spatula_mesher.hpp"
#include "geometry/spatula_shape.hpp"

#include <Teuchos_ParameterList.hpp>

#include <optional>
#include <string>

namespace spatula::app {

struct OutputParameters {
  std::string directory = "spatula-output";
  bool overwrite = true;           // replace an earlier result of this program
  bool write_mesh = true;
  int field_interval = 0;          // write fields every this many converged steps (0: start and end only)
  bool convergence_tables = false;   // print every Newton iteration
  double checkpoint_minutes = 10.0;  // wall-clock minutes between 'last state' checkpoints (0: only at a stop)
  int tangent_spectrum = 0;          // inverse iterations for spectrum.csv at every converged state (0: none)
  static void declare(Teuchos::ParameterList& output);
  static OutputParameters from(const Teuchos::ParameterList& output);
};

struct Scene {
  geometry::ShapeParameters geometry;
  mesh::MeshParameters mesh;
  OutputParameters output;
  discretization::SolidParameters material;
  contact::AdhesionParameters adhesion;
  LoadingParameters loading;
  solvers::LinearSolverParameters linear_solver;
  solvers::NewtonParameters newton;
  JobParameters job;
  bool resume = false;                // go on with a stopped run (command line --resume): restart file = its state
  // Stop once the rotation's checkpoint at this inclination [deg] is written (command line --stop-after-checkpoint)
  std::optional<double> stop_after_checkpoint;
  Teuchos::ParameterList validated;   // the full list with defaults filled in (echoed to the output)
};

// The enrichment of the node space: the adhesion's (Q1C1 or Q1C2), plain Q1C1 without adhesion.
discretization::Enrichment enrichment_of(const Scene& scene);

// All valid keys with defaults and docs, in sublists "Geometry", "Mesh", "Output", "Material", "Loading",
// "Linear Solver", "Nonlinear Solver", "Adhesion", "Job".
Teuchos::ParameterList valid_scene_parameters();
// Validates a user's list (throws parameters::InputError) and reads it into typed parameters.
Scene read_scene(Teuchos::ParameterList user);

}  // namespace spatula::app
