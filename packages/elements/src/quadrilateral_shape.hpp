#pragma once
// Shape functions of a quadrilateral face on [-1, 1]^2: bilinear (4 nodes) and biquadratic Lagrange (9 nodes). The
// contact faces interpolate with them; the Q1C2 solid element (Hex13Shape) combines them through the thickness.
// evaluate(s, t, N, dN): N[k] and dN[k] = {dN/ds, dN/dt}.
#include <Kokkos_Core.hpp>

namespace spatula::elements {

// Bilinear face: corners (-1,-1), (1,-1), (1,1), (-1,1).
struct Quad4Surface {
  static constexpr int nodes = 4;
  KOKKOS_INLINE_FUNCTION static void evaluate(double s, double t, double N[4], double dN[4][2])
  {
    const double cs[4] = {-1, 1, 1, -1}, ct[4] = {-1, -1, 1, 1};
    for (int k = 0; k < 4; ++k) {
      N[k] = 0.25 * (1 + cs[k] * s) * (1 + ct[k] * t);
      dN[k][0] = 0.25 * cs[k] * (1 + ct[k] * t);
      dN[k][1] = 0.25 * ct[k] * (1 + cs[k] * s);
    }
  }
};

// Biquadratic Lagrange face: corners as Quad4, then mid-edges (0,-1), (1,0), (0,1), (-1,0), then the centre.
struct Quad9Surface {
  static constexpr int nodes = 9;
  KOKKOS_INLINE_FUNCTION static void lagrange(double x, double L[3], double dL[3])   // at -1, 0, 1
  {
    L[0] = 0.5 * x * (x - 1);
    L[1] = (1 - x) * (1 + x);
    L[2] = 0.5 * x * (x + 1);
    dL[0] = x - 0.5;
    dL[1] = -2 * x;
    dL[2] = x + 0.5;
  }
  KOKKOS_INLINE_FUNCTION static void evaluate(double s, double t, double N[9], double dN[9][2])
  {
    constexpr int is[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, it[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
    double Ls[3], dLs[3], Lt[3], dLt[3];
    lagrange(s, Ls, dLs);
    lagrange(t, Lt, dLt);
    for (int k = 0; k < 9; ++k) {
      N[k] = Ls[is[k]] * Lt[it[k]];
      dN[k][0] = dLs[is[k]] * Lt[it[k]];
      dN[k][1] = Ls[is[k]] * dLt[it[k]];
    }
  }
};

// The area element |X_,s x X_,t| of a face with nodes Xn at a point where the shape functions' derivatives are dN
// (times the point's Gauss weights, the area the point stands for).
template <class Surface>
KOKKOS_INLINE_FUNCTION double area_element(const double dN[Surface::nodes][2], const double Xn[Surface::nodes][3])
{
  double Xs[3] = {0, 0, 0}, Xt[3] = {0, 0, 0};
  for (int k = 0; k < Surface::nodes; ++k)
    for (int i = 0; i < 3; ++i) {
      Xs[i] += dN[k][0] * Xn[k][i];
      Xt[i] += dN[k][1] * Xn[k][i];
    }
  const double normal[3] = {Xs[1] * Xt[2] - Xs[2] * Xt[1], Xs[2] * Xt[0] - Xs[0] * Xt[2],
                            Xs[0] * Xt[1] - Xs[1] * Xt[0]};
  return ::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
}

}  // namespace spatula::elements
