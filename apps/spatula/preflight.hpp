#pragma once
// Everything about a run that can be checked without solving, checked before anything is computed or written
// (and by --validate-only): the output directory, the memory the mesh and solver need, the mesh's elements, the
// rank count against the mesh, the restart file. Each check throws parameters::InputError naming the key(s) to
// change and why.
#include "scene.hpp"

#include "mesh/hex_mesh.hpp"
#include "mesh/partition.hpp"

#include <cstdint>
#include <string>

namespace spatula::app {

// For `spatula scene.xml --resume`: finds the run of this scene that was stopped (killed, interrupted or failed)
// in 'Output/directory' and points the scene at its 'last state' checkpoint (Scene::resume, the restart file).
// Returns the stopped run's directory (<directory>.partial or .incomplete). Throws parameters::InputError when there
// is none, when it was made with another geometry, mesh, material, adhesion or loading (but for the jump's
// 'maximum iterations', 'method' and 'trust region from': a descent stopped at its limit goes on with a larger one, and
// either method ends on the same stable state), or when the scene cannot be resumed (stiction anchors set at a
// restart, in a checkpoint of a version that did not store them).
std::string prepare_resume(Scene& scene);
// Where a resumed run's checkpoint lies once its directory is the staging directory again.
std::string resumed_checkpoint_file(const Scene& scene);

// For `--stop-after-checkpoint THETA`: sets Scene::stop_after_checkpoint once THETA is one of the inclinations where
// the scene's rotation writes checkpoints and, for a resumed run (after prepare_resume), one it has not passed yet;
// else throws parameters::InputError naming the option, the value and the inclinations allowed.
void set_stop_after_checkpoint(Scene& scene, double theta_y);

// `scene_file` is the scene's own file (empty for the embedded scene): the run must not replace it either.
void check_output_directory(const Scene& scene, const std::string& scene_file);

struct MemoryEstimate {
  std::int64_t nodes = 0, unknowns = 0, matrix_entries = 0;
  double bytes = 0.0;             // peak of the whole run, all ranks together
  double available_bytes = 0.0;   // the tightest memory limit of the job (resource_limits.hpp), all ranks together
  std::string available_source, available_remedy;   // which limit that is, and how to raise it
  solvers::LinearSolverType solver = solvers::LinearSolverType::mumps;   // the scene's, or what 'auto' chose
  double fixed_nodes = 0.0, refined_nodes = 0.0;   // nodes at refinement factor r: fixed + refined r^2
  double nodes_at(int r) const { return fixed_nodes + refined_nodes * r * r; }
};
// Estimated from the node counts of the scene's mesh at refinement factors 1 and 2 (cheap), extrapolated to the
// requested refinement, so that a mesh too large for the machine (or the job's limits) is refused before it is made. The direct solver's share is calibrated on the fine
// mesh's measured peak (docs/performance.md) and grown as unknowns^(4/3) (nested-dissection fill in 3D).
MemoryEstimate estimate_memory(const Scene& scene, std::int64_t unrefined_nodes, std::int64_t refined_nodes, int ranks);
void check_memory(const Scene& scene, const MemoryEstimate& estimate);

// Meshes the scene's spatula and checks every element (det J > 0 at its Gauss points, not degenerate); a geometry
// that cannot be meshed is an InputError naming the part, the parameters that shape it and, for those the scene
// moved from the paper's values, how far they may go with the others as given.
mesh::HexMesh make_checked_mesh(const Scene& scene, const geometry::SpatulaShape& shape);
// The scene's mesh, made only once the memory it needs is known to be there: the meshes at refinement factors 1 and 2
// first (checked, and the measure of what the requested one needs), then the requested one; `estimate` is filled in.
mesh::HexMesh make_mesh_within_memory(const Scene& scene, const geometry::SpatulaShape& shape, int ranks,
                                      MemoryEstimate& estimate);
// Every rank has elements to assemble.
void check_ranks(const mesh::HexMesh& mesh, const mesh::Partition& partition);

}  // namespace spatula::app
