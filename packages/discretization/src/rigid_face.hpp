#pragma once
// Rigid motion of the shaft end face: a rotation alpha about the Y axis through the face centre c and a
// translation w along a fixed lift direction d in the X-Z plane (the spatula: d = e_z, X held). A node at X moves by
//
//   u(alpha, w) = w d + (R(alpha) - I)(X - c),   R(alpha) = [[cos, 0, sin], [0, 1, 0], [-sin, 0, cos]],
//
// so positive alpha steepens the shaft (theta_y = theta_s + alpha). The two "master" unknowns alpha and w replace
// the face nodes' displacements; each is either prescribed or free (then its residual, the net moment or force on
// the face, is zero).
#include <Kokkos_Core.hpp>

#include <cmath>

namespace spatula::discretization {

enum class Master : int { rotation = 0, lift = 1 };
constexpr int master_count = 2;

// u and its derivatives for one face node with offset d = X - c.
struct RigidFaceMotion {
  double u[3];
  double du_dalpha[3];
  double d2u_dalpha2[3];   // du/dw = the lift direction; all other second derivatives vanish
};

KOKKOS_INLINE_FUNCTION RigidFaceMotion rigid_face_motion(double alpha, double w, const double d[3],
                                                         const double lift[3])
{
  const double c = ::cos(alpha), s = ::sin(alpha);
  RigidFaceMotion m;
  m.u[0] = (c - 1.0) * d[0] + s * d[2] + w * lift[0];
  m.u[1] = 0.0;
  m.u[2] = -s * d[0] + (c - 1.0) * d[2] + w * lift[2];
  m.du_dalpha[0] = -s * d[0] + c * d[2];
  m.du_dalpha[1] = 0.0;
  m.du_dalpha[2] = -c * d[0] - s * d[2];
  m.d2u_dalpha2[0] = -c * d[0] - s * d[2];
  m.d2u_dalpha2[1] = 0.0;
  m.d2u_dalpha2[2] = s * d[0] - c * d[2];
  return m;
}

}  // namespace spatula::discretization
