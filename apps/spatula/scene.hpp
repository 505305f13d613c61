#pragma once
// A scene: the whole XML input of one run, validated against the parameters every package declares.
#include "spatula_mesher.hpp"
#include "spatula_shape.hpp"

#include <Teuchos_ParameterList.hpp>

#include <string>

namespace spatula::app {

struct OutputParameters {
  std::string directory = "spatula-output";
  bool write_mesh = true;
  static void declare(Teuchos::ParameterList& output);
  static OutputParameters from(const Teuchos::ParameterList& output);
};

struct Scene {
  geometry::ShapeParameters geometry;
  mesh::MeshParameters mesh;
  OutputParameters output;
  Teuchos::ParameterList validated;   // the full list with defaults filled in (echoed to the output)
};

// All valid keys with defaults and docs, in sublists "Geometry", "Mesh", "Output".
Teuchos::ParameterList valid_scene_parameters();
// Validates a user's list (throws parameters::InputError) and reads it into typed parameters.
Scene read_scene(Teuchos::ParameterList user);

}  // namespace spatula::app
