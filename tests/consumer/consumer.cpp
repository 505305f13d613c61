// Meshes a spatula with a non-default pad through the installed library and checks the result.
#include <mesh/spatula_mesher.hpp>
#include <mesh/mesh_summary.hpp>

#include <iostream>

int main()
{
  spatula::geometry::ShapeParameters parameters;
  parameters.l_p = 420.0;
  const spatula::geometry::SpatulaShape shape(parameters);
  const auto mesh = spatula::mesh::mesh_spatula(shape, spatula::mesh::MeshParameters{});
  const auto summary = spatula::mesh::summarize(mesh, "coarse");
  std::cout << "consumer: " << summary.elements << " hexahedra, contact area " << summary.contact_area << " nm^2\n";
  return summary.elements > 0 && summary.min_gauss_jacobian > 0.0 ? 0 : 1;
}
