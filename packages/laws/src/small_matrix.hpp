#pragma once
// 3x3 matrix helpers on plain arrays, usable inside Kokkos kernels.
#include <Kokkos_Core.hpp>

namespace spatula::laws {

KOKKOS_INLINE_FUNCTION double determinant(const double a[3][3])
{
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

// inverse = a^-1; returns det a (the inverse is left unset when det a == 0).
KOKKOS_INLINE_FUNCTION double invert(const double a[3][3], double inverse[3][3])
{
  const double det = determinant(a);
  if (det == 0.0) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) inverse[i][j] = 0.0;
    return det;
  }
  const double s = 1.0 / det;
  inverse[0][0] = s * (a[1][1] * a[2][2] - a[1][2] * a[2][1]);
  inverse[0][1] = s * (a[0][2] * a[2][1] - a[0][1] * a[2][2]);
  inverse[0][2] = s * (a[0][1] * a[1][2] - a[0][2] * a[1][1]);
  inverse[1][0] = s * (a[1][2] * a[2][0] - a[1][0] * a[2][2]);
  inverse[1][1] = s * (a[0][0] * a[2][2] - a[0][2] * a[2][0]);
  inverse[1][2] = s * (a[0][2] * a[1][0] - a[0][0] * a[1][2]);
  inverse[2][0] = s * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  inverse[2][1] = s * (a[0][1] * a[2][0] - a[0][0] * a[2][1]);
  inverse[2][2] = s * (a[0][0] * a[1][1] - a[0][1] * a[1][0]);
  return det;
}

}  // namespace spatula::laws
