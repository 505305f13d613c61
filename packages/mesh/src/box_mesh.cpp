#include "mesh/box_mesh.hpp"

#include <algorithm>

namespace spatula::mesh {

HexMesh box_mesh(const BoxParameters& p)
{
  const auto [nx, ny, nz] = p.elements;
  HexMeshBuilder builder;
  auto id = [&](int i, int j, int k) { return std::int64_t(i) + std::int64_t(nx + 1) * (j + std::int64_t(ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        HexMeshBuilder::Flags flags = 0;
        if (j == 0) flags |= HexMeshBuilder::flag(Boundary::symmetry);
        if (i == nx) flags |= HexMeshBuilder::flag(Boundary::end_face);
        if (k == 0) flags |= HexMeshBuilder::flag(Boundary::contact);
        builder.add_node({p.lengths[0] * i / nx, p.lengths[1] * j / ny, p.lengths[2] * k / nz}, flags);
      }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        builder.add_element({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                             id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)},
                            Part::thin_pad);
  double smallest = p.lengths[0] / nx;
  for (int d = 1; d < 3; ++d) smallest = std::min(smallest, p.lengths[d] / p.elements[d]);
  return builder.finish(1e-9 * smallest);
}

}  // namespace spatula::mesh
