#pragma once
// Runs a scene's loading on the meshed spatula: builds the distributed system and solvers, steps the end face,
// prints a progress line per converged step, and writes curve.csv and field states (rank 0).
#include "mesh_output.hpp"
#include "output_directory.hpp"
#include "scene.hpp"

#include <Teuchos_Comm.hpp>

#include <optional>
#include <ostream>

namespace spatula::app {

// Returns the failure (step, load, reason) if the load path could not be followed to its end.
std::optional<analysis::Failure> run_simulation(const Scene& scene, const geometry::SpatulaShape& shape,
                                                const mesh::HexMesh& mesh, const mesh::Partition& partition,
                                                Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                                const io::OutputDirectory* directory, io::XdmfOutput* fields,
                                                std::ostream& out);

}  // namespace spatula::app
