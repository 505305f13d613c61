#pragma once
// Checkpoints of converged states in HDF5 (checkpoints.h5 in the output directory), and restarts from them:
// a rotation run leaves its states at chosen inclinations, and pull-off runs start from them (as the paper does).
//
// A checkpoint stores the displacements of every node of the node space (mesh and enrichment nodes), the three
// end-face masters and the path history (step, external work), under /checkpoints/theta_y=<deg>, with a
// signature (node and element counts, enrichment, geometry) checked on restart.
#include "load_stepping.hpp"
#include "scene.hpp"

#include <string>

namespace spatula::app {

// The label of a checkpoint taken at inclination theta_y [deg].
std::string checkpoint_label(double theta_y_degrees);

// Rank 0 writes (all ranks must call: the state is gathered).
void write_checkpoint(const std::string& file, double theta_y_degrees, const discretization::DiscreteSystem& system,
                      const discretization::Vector& x, const analysis::LoadPoint& point, const Scene& scene);

// Reads a checkpoint into x and returns the path history; throws parameters::InputError naming the file and
// label if missing or made for another mesh.
analysis::LoadPoint read_checkpoint(const std::string& file, double theta_y_degrees,
                                    const discretization::DiscreteSystem& system, discretization::Vector& x,
                                    const Scene& scene);

}  // namespace spatula::app
