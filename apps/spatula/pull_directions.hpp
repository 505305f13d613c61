#pragma once
// The directions in which the end face is lifted and slid ('Loading/pull angle' beta, from the substrate in the X-Z
// plane): lift d = (cos beta, 0, sin beta), slide e = (sin beta, 0, -cos beta), so beta = 90 deg (the default, the
// paper's pull) lifts along Z and slides along X. The load path moves and loads the face along d and e (its masters,
// the lift and slide stages, the free and held motions); what the program reports (curve.csv's u_z, u_x, P_z, P_x,
// the progress line) is in the substrate's Z and X.
#include <array>
#include <cmath>

namespace spatula::app {

struct PullDirections {
  std::array<double, 3> lift{0.0, 0.0, 1.0}, slide{1.0, 0.0, 0.0};

  static PullDirections at(double beta_degrees)
  {
    PullDirections directions;
    if (beta_degrees == 90.0) return directions;   // exactly Z and X
    const double beta = beta_degrees * M_PI / 180.0;
    directions.lift = {std::cos(beta), 0.0, std::sin(beta)};
    directions.slide = {std::sin(beta), 0.0, -std::cos(beta)};
    return directions;
  }
  // A motion or force given along the lift and slide directions, in the substrate's X and Z.
  double x(double along_lift, double along_slide) const { return along_lift * lift[0] + along_slide * slide[0]; }
  double z(double along_lift, double along_slide) const { return along_lift * lift[2] + along_slide * slide[2]; }
  // And back: a motion in X and Z along the lift and slide directions (d and e are orthonormal in the X-Z plane).
  double along_lift(double x, double z) const { return x * lift[0] + z * lift[2]; }
  double along_slide(double x, double z) const { return x * slide[0] + z * slide[2]; }
};

}  // namespace spatula::app
