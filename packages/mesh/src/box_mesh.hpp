#pragma once
// A structured box [0, Lx] x [0, Ly] x [0, Lz] of trilinear hexahedra for tests and benchmarks (bars, strips,
// blocks). Sets: symmetry = the face Y = 0, end_face = the face X = Lx, contact = the face Z = 0.
#include "mesh/hex_mesh.hpp"

#include <array>

namespace spatula::mesh {

struct BoxParameters {
  std::array<double, 3> lengths{1.0, 1.0, 1.0};
  std::array<int, 3> elements{1, 1, 1};
};

HexMesh box_mesh(const BoxParameters& parameters);

}  // namespace spatula::mesh
