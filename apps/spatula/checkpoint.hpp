#pragma once
// Checkpoints of converged states in HDF5 (checkpoints.h5 in the output directory), and restarts from them:
// a rotation run leaves its states at chosen inclinations, and pull-off runs start from them (as the paper does);
// a run that is interrupted or fails leaves its last converged state, to go on from.
//
// A checkpoint stores the displacements of every node of the node space (mesh and enrichment nodes), the three
// end-face masters (with the 'Loading/pull angle' whose directions they move along: a restart with another angle
// turns them into its own), the path history (step, external work) and the stage (rotation or lift, and where the
// lift began), under /checkpoints/<label>, with a signature (node and element counts, enrichment, geometry, material)
// checked on restart. A run whose stiction anchors were set at its restart state ('Adhesion/stiction anchors' =
// 'restart state') also stores that state's displacements (/anchors), so that a resumed run measures the travel
// from the same anchors. A contact law with state (adhesive friction) stores its points' committed histories
// (/contact history, face after face in the node space's order), which a restart requires (unless its anchors are
// set at the restart state, where it then starts unstrained). A last state taken inside a jump past an instability
// (a periodic checkpoint during its energy descent, a signal, or the descent's iteration limit) also stores the
// descent's state (/jump displacements, /jump masters) and where it stands (/jump: master, value, shift, scale,
// iterations): a run resumed from it goes on with the descent instead of starting the jump again.
#include "analysis/load_stepping.hpp"
#include "scene.hpp"

#include <optional>
#include <string>

namespace spatula::app {

// The label of a checkpoint taken at inclination theta_y [deg], and of the last converged state of a stopped run.
std::string checkpoint_label(double theta_y_degrees);
inline const char* last_state_label = "last state";
// The label a scene restarts from ('Loading/restart from', 'Loading/restart theta_y').
std::string restart_label(const LoadingParameters& loading);

// Where on its path a checkpointed state was: in the stage of this index ('Loading/Stages', or 0 the rotation and 1
// the lift of the fixed types), which began at `start` (its moved motion there, in the stage's unit: deg or nm).
struct PathStage {
  int index = 0;
  double start = 0.0;
};

// What a run needs, beyond the state, to go on as if it had never stopped (`spatula --resume`): the energies
// its curve counts from, the peaks its detachment test compares with, its wall time so far and how many field
// states it had written, and the increment its step controller would have tried next.
struct RunRecord {
  double initial_internal_energy = 0.0, initial_contact_energy = 0.0;   // the half model's, as LoadPoint's
  double peak_moment = 0.0, peak_force = 0.0;
  double seconds = 0.0;
  int field_states = 0;
  analysis::StepControllerState step_control;
};

// Rank 0 writes (all ranks must call: the state is gathered). A label already in the file is kept, except the last
// state, which is replaced. The file is replaced as a whole (written beside it, then renamed): a run killed while
// writing leaves the checkpoints it had. `anchors`: the state the stiction anchors were set at, or nullptr.
// `jump`: a jump under way from x (its energy descent's state, /jump and /jump displacements), or nullptr.
void write_checkpoint(const std::string& file, const std::string& label, const discretization::DiscreteSystem& system,
                      const discretization::Vector& x, const analysis::LoadPoint& point, const PathStage& stage,
                      const Scene& scene, const RunRecord& record, const discretization::Vector* anchors = nullptr,
                      const analysis::LoadPath::JumpInProgress* jump = nullptr);
// The jump under way stored with the scene's restart checkpoint, if it holds one (all ranks read).
std::optional<analysis::LoadPath::JumpInProgress> read_jump_in_progress(const Scene& scene,
                                                                       const discretization::DiscreteSystem& system);

// Whether `file` holds the checkpoint `label` (false where it cannot be read).
bool holds_checkpoint(const std::string& file, const std::string& label);
// Whether `file` holds a complete 'last state' checkpoint with its run record (a run that can be resumed).
bool resumable(const std::string& file);
// Whether the 'last state' checkpoint in `file` holds the state its stiction anchors were set at.
bool holds_anchors(const std::string& file);
// Reads the anchors' state stored with the scene's restart checkpoint into `anchors` (check holds_anchors before).
void read_anchors(const Scene& scene, const discretization::DiscreteSystem& system, discretization::Vector& anchors);
// The run record of the scene's restart checkpoint.
RunRecord read_run_record(const Scene& scene);

// Checks, before anything is computed or written, that the scene's restart file holds its checkpoint and that the
// checkpoint was made for this geometry, mesh, enrichment and material and lies in a stage of this scene's path;
// throws parameters::InputError naming 'Loading/restart file' and what does not match. `nodes` is this scene's node
// space.
void check_checkpoint(const Scene& scene, const discretization::NodeSpace& nodes);

// Reads the scene's checkpoint into x (and a contact law's histories into the system) and returns the path history
// (checked by check_checkpoint before).
analysis::LoadPoint read_checkpoint(const Scene& scene, discretization::DiscreteSystem& system,
                                    discretization::Vector& x, PathStage& stage);

}  // namespace spatula::app
