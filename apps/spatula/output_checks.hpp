#pragma once
// The output directory as a shared resource: owned by one live run (its lock), and with room for what the run will
// write (its size estimated from the mesh and the load path, against the free space of the file system).
#include "scene.hpp"

#include "io/run_lock.hpp"
#include "mesh/hex_mesh.hpp"

#include <memory>
#include <string>

namespace spatula::app {

// Takes the lock of 'Output/directory' (its parent directories made if missing), then checks the directory again
// under it (another run may have changed it since the preflight looked), and, with --resume, that the stopped run
// `resume_from` is still there. A directory another live run writes is an InputError naming it and that process.
std::unique_ptr<io::RunLock> lock_output_directory(const Scene& scene, const std::string& scene_file,
                                                   const std::string& resume_from);

// Bytes the run will write at most, on the mesh's nodes and elements: the mesh and its field states (every
// 'Output/field interval' steps of the load path's estimated step count), the checkpoints file (each checkpoint
// inclination and the last state, twice while it is replaced) and the curve; and the largest single file.
struct OutputEstimate {
  double total = 0.0, largest = 0.0;
  std::string largest_file;
};
OutputEstimate estimate_output(const Scene& scene, const mesh::HexMesh& mesh);
// An InputError with the estimate when the file system of 'Output/directory' has less free space than the run will
// write, or when its largest file is above the job's file-size limit.
void check_output_limits(const Scene& scene, const OutputEstimate& estimate);

}  // namespace spatula::app
