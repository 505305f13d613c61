#pragma once
// Rigid motion of the shaft end face: a rotation alpha about the Y axis through the face centre c, a lift w along
// a direction d and a slide s along a direction e (d, e unit vectors in the X-Z plane; the spatula: d = e_z,
// e = e_x with s held at 0). A node at X moves by
//
//   u(alpha, w, s) = w d + s e + (R(alpha) - I)(X - c),   R(alpha) = [[cos, 0, sin], [0, 1, 0], [-sin, 0, cos]],
//
// so positive alpha steepens the shaft (theta_y = theta_s + alpha). The three "master" unknowns replace the face
// nodes' displacements; each is either prescribed or free (then its residual, the net moment or force on the face
// along d or e, is zero).
#include <Kokkos_Core.hpp>

#include <cmath>

namespace spatula::discretization {

enum class Master : int { rotation = 0, lift = 1, slide = 2 };
constexpr int master_count = 3;

// u and its derivatives for one face node with offset X - c (du/dw = d and du/ds = e are constant).
struct RigidFaceMotion {
  double u[3];
  double du_dalpha[3];
  double d2u_dalpha2[3];   // all other second derivatives vanish
};

struct RigidFaceDirections {
  double lift[3] = {0.0, 0.0, 1.0};
  double slide[3] = {1.0, 0.0, 0.0};
};

KOKKOS_INLINE_FUNCTION RigidFaceMotion rigid_face_motion(const double masters[master_count], const double offset[3],
                                                         const RigidFaceDirections& directions)
{
  const double c = ::cos(masters[0]), s = ::sin(masters[0]);
  const double* d = offset;
  RigidFaceMotion m;
  m.u[0] = (c - 1.0) * d[0] + s * d[2];
  m.u[1] = 0.0;
  m.u[2] = -s * d[0] + (c - 1.0) * d[2];
  for (int i = 0; i < 3; ++i) m.u[i] += masters[1] * directions.lift[i] + masters[2] * directions.slide[i];
  m.du_dalpha[0] = -s * d[0] + c * d[2];
  m.du_dalpha[1] = 0.0;
  m.du_dalpha[2] = -c * d[0] - s * d[2];
  m.d2u_dalpha2[0] = -c * d[0] - s * d[2];
  m.d2u_dalpha2[1] = 0.0;
  m.d2u_dalpha2[2] = s * d[0] - c * d[2];
  return m;
}

}  // namespace spatula::discretization
