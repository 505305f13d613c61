#pragma once
// The contact face the face tests integrate: 6 nm x 5 nm on Z = 0, slightly skewed, its nodes (Q1C1 or Q1C2 order)
// with their parent coordinates (s, t) in [-1, 1]^2, from which each test makes its own displacement.
#include <array>

namespace spatula::test {

inline const double face_node_parameters[9][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1},
                                                  {1, 0},   {0, 1},  {-1, 0}, {0, 0}};

template <class Surface>
void skewed_face(double X[Surface::nodes][3])
{
  const double corners[4][2] = {{0.0, 0.0}, {6.0, 0.5}, {6.5, 5.0}, {0.2, 5.2}};
  for (int k = 0; k < Surface::nodes; ++k) {
    const double s = face_node_parameters[k][0], t = face_node_parameters[k][1];
    const double N[4] = {0.25 * (1 - s) * (1 - t), 0.25 * (1 + s) * (1 - t), 0.25 * (1 + s) * (1 + t),
                         0.25 * (1 - s) * (1 + t)};
    X[k][0] = X[k][1] = X[k][2] = 0.0;
    for (int c = 0; c < 4; ++c) {
      X[k][0] += N[c] * corners[c][0];
      X[k][1] += N[c] * corners[c][1];
    }
  }
}

}  // namespace spatula::test
