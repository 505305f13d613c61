#pragma once
// The trilinear hexahedron (Hex8) reference element: node order, faces, shape functions and derivatives.
// Header-only and usable inside Kokkos kernels: everything works on fixed-size arrays.
#include <Kokkos_Core.hpp>

namespace spatula::mesh {

// Reference coordinates of the eight nodes: bottom face (zeta = -1) counter-clockwise seen from +zeta, then top.
KOKKOS_INLINE_FUNCTION double hex_node_coordinate(int node, int direction)
{
  constexpr double corners[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  return corners[node][direction];
}

// Local faces, each ordered counter-clockwise seen from outside (outward normal by the right-hand rule).
// Face 4 is the bottom (zeta = -1), face 5 the top.
KOKKOS_INLINE_FUNCTION int hex_face_node(int face, int corner)
{
  constexpr int faces[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {0, 4, 7, 3}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  return faces[face][corner];
}
constexpr int hex_face_count = 6;

// N_a(xi) = (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a) / 8 and dN_a / dxi_j.
KOKKOS_INLINE_FUNCTION void hex_shape(const double xi[3], double shape[8], double gradient[8][3])
{
  for (int a = 0; a < 8; ++a) {
    double factor[3], derivative[3];
    for (int j = 0; j < 3; ++j) {
      const double corner = hex_node_coordinate(a, j);
      factor[j] = 0.5 * (1.0 + xi[j] * corner);
      derivative[j] = 0.5 * corner;
    }
    shape[a] = factor[0] * factor[1] * factor[2];
    gradient[a][0] = derivative[0] * factor[1] * factor[2];
    gradient[a][1] = factor[0] * derivative[1] * factor[2];
    gradient[a][2] = factor[0] * factor[1] * derivative[2];
  }
}

// Jacobian matrix J_ij = d x_i / d xi_j at xi for nodal coordinates x[8][3]; returns det J.
KOKKOS_INLINE_FUNCTION double hex_jacobian(const double x[8][3], const double xi[3], double jacobian[3][3])
{
  double shape[8], gradient[8][3];
  hex_shape(xi, shape, gradient);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (int a = 0; a < 8; ++a) sum += x[a][i] * gradient[a][j];
      jacobian[i][j] = sum;
    }
  return jacobian[0][0] * (jacobian[1][1] * jacobian[2][2] - jacobian[1][2] * jacobian[2][1]) -
         jacobian[0][1] * (jacobian[1][0] * jacobian[2][2] - jacobian[1][2] * jacobian[2][0]) +
         jacobian[0][2] * (jacobian[1][0] * jacobian[2][1] - jacobian[1][1] * jacobian[2][0]);
}

}  // namespace spatula::mesh
