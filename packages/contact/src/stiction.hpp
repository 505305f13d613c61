#pragma once
// The stiction variant of the adhesion law (paper Sec. 4.3, eq. 27; docs/adhesion.md) on a flat substrate. A surface
// point is attracted to its anchor, the point of the substrate below where it started (its reference position, or
// its position at the state where a run re-anchored the law), with the
// Lennard-Jones law of the total separation r_k = |g| = sqrt(r_s^2 + r_a^2), g = x - anchor, r_a the tangential
// travel; the force acts along g (equal law in mode I and mode II). The radial law is unstable in compression, so
// its attraction is kept and the repulsion is replaced by the normal law acting only in compression:
//
//   phi(g) = phi_LJ(max(r_k, r_eq)) + [ phi_LJ(r_s) - phi_LJ(r_eq) ]  (second term only for r_s < r_eq)
//
// With r_a = 0 (r_k = r_s) this is phi_LJ(r_s) for every r_s: the frictionless law. Both parts are C1 at r_eq
// (phi_LJ'(r_eq) = 0).
#include "contact/lennard_jones.hpp"

namespace spatula::contact {

struct StictionLaw {
  LennardJones law;
  double substrate_height = 0.0;

  // Energy density, gradient d phi / dx and (if H) Hessian at current position x of a point whose anchor is at
  // (A_0, A_1) on the substrate. Returns false if both parts are beyond the cut-off.
  KOKKOS_INLINE_FUNCTION bool evaluate(const double A[3], const double x[3], double& phi, double gradient[3],
                                       double (*H)[3]) const
  {
    const double g[3] = {x[0] - A[0], x[1] - A[1], x[2] - substrate_height};
    const double r_s = g[2], r_k = ::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    const double r_eq = law.equilibrium_gap();
    double p, d1, d2, p_eq, unused1, unused2;
    law.exact(r_eq, p_eq, unused1, unused2);
    for (int i = 0; i < 3; ++i) {
      gradient[i] = 0.0;
      if (H)
        for (int j = 0; j < 3; ++j) H[i][j] = 0.0;
    }
    bool active = false;
    // Attraction of the anchor along g.
    if (r_k > r_eq) {
      active = law.evaluate(r_k, p, d1, d2);
      phi = p;
      double e[3];
      for (int i = 0; i < 3; ++i) {
        e[i] = g[i] / r_k;
        gradient[i] = d1 * e[i];
      }
      if (H)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) H[i][j] = d2 * e[i] * e[j] + d1 / r_k * ((i == j ? 1.0 : 0.0) - e[i] * e[j]);
    } else {
      phi = p_eq;
      active = true;
    }
    // Normal repulsion in compression.
    if (r_s < r_eq) {
      law.evaluate(r_s, p, d1, d2);
      phi += p - p_eq;
      gradient[2] += d1;
      if (H) H[2][2] += d2;
      active = true;
    }
    return active;
  }
};

}  // namespace spatula::contact
