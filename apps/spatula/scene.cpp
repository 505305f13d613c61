#include "scene.hpp"

#include "parameter_validation.hpp"

namespace spatula::app {

void OutputParameters::declare(Teuchos::ParameterList& output)
{
  parameters::declare_string(output, "directory", "spatula-output",
                             "directory for all results (replaced atomically at the end of the run)");
  parameters::declare_bool(output, "write mesh", true, "write the mesh as HDF5 + XDMF");
}

OutputParameters OutputParameters::from(const Teuchos::ParameterList& output)
{
  OutputParameters p;
  p.directory = output.get<std::string>("directory");
  p.write_mesh = output.get<bool>("write mesh");
  if (p.directory.empty()) throw parameters::InputError("parameter 'Output/directory' must not be empty");
  return p;
}

Teuchos::ParameterList valid_scene_parameters()
{
  Teuchos::ParameterList valid("spatula scene");
  geometry::ShapeParameters::declare(
      parameters::declare_sublist(valid, "Geometry", "the twelve spatula parameters of the paper's Table 2 [nm]"));
  mesh::MeshParameters::declare(parameters::declare_sublist(valid, "Mesh", "hexahedral mesh density"));
  OutputParameters::declare(parameters::declare_sublist(valid, "Output", "result files"));
  return valid;
}

Scene read_scene(Teuchos::ParameterList user)
{
  parameters::validate(user, valid_scene_parameters());
  Scene scene;
  scene.geometry = geometry::ShapeParameters::from(user.sublist("Geometry"));
  scene.mesh = mesh::MeshParameters::from(user.sublist("Mesh"));
  scene.output = OutputParameters::from(user.sublist("Output"));
  scene.validated = user;
  return scene;
}

}  // namespace spatula::app
