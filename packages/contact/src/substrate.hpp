#pragma once
// Rigid substrates as signed distance functions d(x) with their gradient n = grad d (the substrate normal at the
// closest point) and Hessian grad n (the curvature terms of the contact tangent).
//
//   flat:  the plane z = height;  d = x_z - height, n = e_z, grad n = 0 (no projection).
//   rough: z = base + sum_k z0 exp(-|p - c_k|^2 / h^2) over a triangular lattice c_k of spacing lambda (paper
//          eq. 28); d by closest-point projection (Newton on the surface parameters), n = (-grad S, 1)/|.|,
//          grad n = dn/dxi dxi/dx with dxi/dx from the implicit projection condition.

#include <Kokkos_Core.hpp>

#include <cmath>

namespace spatula::contact {

struct SurfacePoint {
  double distance = 0.0;
  double normal[3] = {0.0, 0.0, 1.0};
  double curvature[3][3] = {};   // grad n = Hessian of d
  double foot[3] = {};           // closest point on the substrate
};

struct FlatSubstrate {
  double height = 0.0;

  // Lower bound of the distance of x to the substrate (cheap test before projecting).
  KOKKOS_INLINE_FUNCTION double distance_bound(const double x[3]) const { return x[2] - height; }

  KOKKOS_INLINE_FUNCTION bool project(const double x[3], SurfacePoint& p) const
  {
    p.distance = x[2] - height;
    p.foot[0] = x[0];
    p.foot[1] = x[1];
    p.foot[2] = height;
    return true;
  }
};

struct RoughSubstrate {
  double base = 0.0;     // z of the substrate between asperities
  double z0 = 4.0;       // asperity height [nm]
  double width = 20.0;   // h [nm]
  double spacing = 100.0;   // lambda [nm]

  KOKKOS_INLINE_FUNCTION double distance_bound(const double x[3]) const { return x[2] - base - z0; }

  // S, grad S, Hessian of S at (x, y): asperities within 6 h contribute (exp(-36) is negligible).
  KOKKOS_INLINE_FUNCTION void surface(double x, double y, double& S, double g[2], double H[2][2]) const
  {
    S = base;
    g[0] = g[1] = 0.0;
    H[0][0] = H[0][1] = H[1][0] = H[1][1] = 0.0;
    const double row = spacing * 0.8660254037844386;   // lambda sqrt(3) / 2
    const double reach = 6.0 * width;
    const int j0 = static_cast<int>(::floor((y - reach) / row)), j1 = static_cast<int>(::ceil((y + reach) / row));
    for (int j = j0; j <= j1; ++j) {
      const double cy = j * row, shift = 0.5 * spacing * j;
      const int i0 = static_cast<int>(::floor((x - reach - shift) / spacing));
      const int i1 = static_cast<int>(::ceil((x + reach - shift) / spacing));
      for (int i = i0; i <= i1; ++i) {
        const double dx = x - (i * spacing + shift), dy = y - cy;
        const double e = z0 * ::exp(-(dx * dx + dy * dy) / (width * width));
        const double a = -2.0 / (width * width);
        S += e;
        g[0] += a * dx * e;
        g[1] += a * dy * e;
        H[0][0] += (a + a * a * dx * dx) * e;
        H[1][1] += (a + a * a * dy * dy) * e;
        H[0][1] += a * a * dx * dy * e;
      }
    }
    H[1][0] = H[0][1];
  }

  // Closest point by Newton on xi = (xi, eta): grad D = (xi - x_t) + (S - x_z) grad S = 0. Returns false if it did
  // not converge (then p holds the graph distance x_z - S(x_t) and the normal there).
  KOKKOS_INLINE_FUNCTION bool project(const double x[3], SurfacePoint& p) const
  {
    double xi[2] = {x[0], x[1]}, S = 0.0, g[2], H[2][2];
    bool converged = false;
    for (int iteration = 0; iteration < 30; ++iteration) {
      surface(xi[0], xi[1], S, g, H);
      const double gap = S - x[2];
      const double G[2] = {xi[0] - x[0] + gap * g[0], xi[1] - x[1] + gap * g[1]};
      const double A[2][2] = {{1.0 + g[0] * g[0] + gap * H[0][0], g[0] * g[1] + gap * H[0][1]},
                              {g[1] * g[0] + gap * H[1][0], 1.0 + g[1] * g[1] + gap * H[1][1]}};
      const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
      if (!(det > 0.0)) break;   // not a minimum: leave it to the fallback
      const double step[2] = {(A[1][1] * G[0] - A[0][1] * G[1]) / det, (A[0][0] * G[1] - A[1][0] * G[0]) / det};
      xi[0] -= step[0];
      xi[1] -= step[1];
      if (::fabs(step[0]) + ::fabs(step[1]) < 1e-13 * (1.0 + spacing)) {
        converged = true;
        break;
      }
    }
    if (!converged) {
      xi[0] = x[0];
      xi[1] = x[1];
    }
    surface(xi[0], xi[1], S, g, H);
    const double m[3] = {-g[0], -g[1], 1.0};
    const double length = ::sqrt(m[0] * m[0] + m[1] * m[1] + 1.0);
    for (int i = 0; i < 3; ++i) p.normal[i] = m[i] / length;
    p.foot[0] = xi[0];
    p.foot[1] = xi[1];
    p.foot[2] = S;
    const double d[3] = {x[0] - xi[0], x[1] - xi[1], x[2] - S};
    p.distance = converged ? d[0] * p.normal[0] + d[1] * p.normal[1] + d[2] * p.normal[2] : x[2] - S;
    // grad n = dn/dxi (3x2) * dxi/dx (2x3), dxi/dx = A^-1 [I_2 | grad S], A the projection Hessian above.
    const double gap = S - x[2];
    const double A[2][2] = {{1.0 + g[0] * g[0] + gap * H[0][0], g[0] * g[1] + gap * H[0][1]},
                            {g[1] * g[0] + gap * H[1][0], 1.0 + g[1] * g[1] + gap * H[1][1]}};
    const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    const double Ainv[2][2] = {{A[1][1] / det, -A[0][1] / det}, {-A[1][0] / det, A[0][0] / det}};
    const double B[2][3] = {{1.0, 0.0, g[0]}, {0.0, 1.0, g[1]}};
    double dxi[2][3];
    for (int a = 0; a < 2; ++a)
      for (int j = 0; j < 3; ++j) dxi[a][j] = Ainv[a][0] * B[0][j] + Ainv[a][1] * B[1][j];
    double dn[3][2];   // (I - n n) dm/dxi / |m|, dm/dxi_b = (-H_0b, -H_1b, 0)
    for (int b = 0; b < 2; ++b) {
      const double dm[3] = {-H[0][b], -H[1][b], 0.0};
      const double projection = p.normal[0] * dm[0] + p.normal[1] * dm[1];
      for (int i = 0; i < 3; ++i) dn[i][b] = (dm[i] - p.normal[i] * projection) / length;
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) p.curvature[i][j] = dn[i][0] * dxi[0][j] + dn[i][1] * dxi[1][j];
    return converged;
  }
};

}  // namespace spatula::contact
