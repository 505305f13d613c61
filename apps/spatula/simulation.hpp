#pragma once
// Runs a scene's loading on the meshed spatula: builds the distributed system and solvers, steps the end face,
// prints a progress line per converged step, and writes curve.csv and field states (rank 0).
#include "io/mesh_output.hpp"
#include "io/output_directory.hpp"
#include "scene.hpp"

#include <Teuchos_Comm.hpp>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace spatula::app {

// Why a run stopped before the end of its load path: a failure (step, load, reason), or a signal (SIGINT,
// SIGTERM) at a converged state. Either way the last converged state is checkpointed as 'last state'.
struct Stop {
  analysis::Failure failure;
  int signal = 0;                    // the signal that interrupted the run, 0 for a failure
  bool checkpointed = false;         // 'last state' written to checkpoints.h5
  std::string stage = "rotation";    // the stage it stopped in (its name)
  discretization::Master moved = discretization::Master::rotation;   // what that stage moves (the load's unit)
  bool force = false;                // that stage moves the force on it [nN], not the motion
  bool paused = false;               // stopped as asked after a checkpoint (--stop-after-checkpoint): exit 0
};

// The cell fields of each field state: tr(sigma) / E, and with a contact law that dissipates (adhesive friction) the
// energy it has dissipated per unit area on the elements of the contact faces [J/m^2]: where the pad has slid.
inline const char* stress_field = "I1";
inline const char* friction_field = "dissipated_by_friction";
std::vector<std::string> cell_field_names(const Scene& scene);

// "rotation", "lift", "slide": a motion of the end face in messages.
const char* motion_name(discretization::Master motion);

// Returns why the run stopped, if the load path could not be followed to its end.
std::optional<Stop> run_simulation(const Scene& scene, const geometry::SpatulaShape& shape,
                                                const mesh::HexMesh& mesh, const mesh::Partition& partition,
                                                Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                                const io::OutputDirectory* directory, io::XdmfOutput* fields,
                                                std::ostream& out);

}  // namespace spatula::app
