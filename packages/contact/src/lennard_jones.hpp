#pragma once
// Van der Waals adhesion between the pad surface and a rigid substrate as a Lennard-Jones surface law of the gap r
// (paper Sec. 3, eqs. 16, 18, 23; docs/adhesion.md), per unit undeformed area, positive T = repulsion:
//
//   phi(r) = A / (2 pi r0^2) [ (1/360) (r0/r)^8 - (1/6) (r0/r)^2 ]
//   T(r)   = -phi'(r) = A / (2 pi r0^3) [ (1/45) (r0/r)^9 - (1/3) (r0/r)^3 ]
//   T'(r)  = -A / (2 pi r0^4) [ (1/5) (r0/r)^10 - (r0/r)^4 ]
//
// r_eq = r0 15^(-1/6) (T = 0), r_min = r0 5^(-1/6) (strongest attraction t_max = sqrt(5) A / (9 pi r0^3)),
// w_adh = -phi(r_eq) = 15^(1/3) A / (16 pi r0^2).
// Regularization in compression (r < r_reg < r_eq): T continues linearly with the slope it has at r_reg,
//   T(r) = T(r_reg) + T'(r_reg) (r - r_reg),  phi(r) = phi(r_reg) - T(r_reg)(r - r_reg) - T'(r_reg)(r - r_reg)^2 / 2,
// so T is C1 and finite for any r (also r <= 0). Cut-off: between r_cut / 2 and r_cut the law is blended into the
// constant phi(r_cut) with the quintic smootherstep S (S = 1 at r_cut / 2, 0 at r_cut, S' = S'' = 0 at both ends),
//   phi_t = phi(r_cut) + S (phi - phi(r_cut)),
// so T and T' stay continuous (a hard cut would make the residual jump as points cross r_cut and stall Newton);
// beyond r_cut T = 0 and phi = phi(r_cut). The law is exact up to r_cut / 2.
#include <Kokkos_Core.hpp>

#include <cmath>

namespace spatula::contact {

struct LennardJones {
  double hamaker = 0.1;   // A_H [nN nm] (1e-19 J)
  double r0 = 0.4;        // [nm]
  double r_reg = 0.0;     // regularization gap [nm] (0: none)
  double r_cut = 1e30;    // cut-off gap [nm]

  KOKKOS_INLINE_FUNCTION double equilibrium_gap() const { return r0 * ::pow(15.0, -1.0 / 6.0); }
  KOKKOS_INLINE_FUNCTION double strongest_attraction_gap() const { return r0 * ::pow(5.0, -1.0 / 6.0); }
  KOKKOS_INLINE_FUNCTION double work_of_adhesion() const
  {
    return ::cbrt(15.0) * hamaker / (16.0 * M_PI * r0 * r0);
  }
  KOKKOS_INLINE_FUNCTION double max_traction() const { return ::sqrt(5.0) * hamaker / (9.0 * M_PI * r0 * r0 * r0); }

  // The unregularized law: phi, phi' = -T, phi'' = -T'.
  KOKKOS_INLINE_FUNCTION void exact(double r, double& phi, double& dphi, double& d2phi) const
  {
    const double s = r0 / r, s2 = s * s, s3 = s2 * s, s4 = s2 * s2, s8 = s4 * s4;
    const double c = hamaker / (2.0 * M_PI * r0 * r0);
    phi = c * (s8 / 360.0 - s2 / 6.0);
    dphi = -(c / r0) * (s8 * s / 45.0 - s3 / 3.0);
    d2phi = (c / (r0 * r0)) * (s8 * s2 / 5.0 - s4);
  }

  // phi''' where the law is exact or regularized (r <= r_cut / 2; 0 below r_reg, where phi is quadratic): the
  // sliding limit of adhesive friction needs it within its own cut-off, which lies there.
  KOKKOS_INLINE_FUNCTION double third_derivative(double r) const
  {
    if (r < r_reg) return 0.0;
    const double s = r0 / r, s2 = s * s, s5 = s2 * s2 * s, s11 = s5 * s5 * s;
    const double c = hamaker / (2.0 * M_PI * r0 * r0);
    return -(c / (r0 * r0 * r0)) * (2.0 * s11 - 4.0 * s5);
  }

  // phi, phi' and phi'' with regularization and cut-off. Returns false beyond the cut-off (all three constant/0).
  KOKKOS_INLINE_FUNCTION bool evaluate(double r, double& phi, double& dphi, double& d2phi) const
  {
    if (r >= r_cut) {
      double d1, d2;
      exact(r_cut, phi, d1, d2);
      dphi = d2phi = 0.0;
      return false;
    }
    const double taper = 0.5 * r_cut;
    if (r > taper) {
      double p, d1, d2, p_cut, unused1, unused2;
      exact(r, p, d1, d2);
      exact(r_cut, p_cut, unused1, unused2);
      const double width = r_cut - taper, t = (r - taper) / width;
      const double S = 1.0 - t * t * t * (10.0 - 15.0 * t + 6.0 * t * t);
      const double dS = -30.0 * t * t * (1.0 - t) * (1.0 - t) / width;
      const double d2S = -60.0 * t * (1.0 - t) * (1.0 - 2.0 * t) / (width * width);
      phi = p_cut + S * (p - p_cut);
      dphi = dS * (p - p_cut) + S * d1;
      d2phi = d2S * (p - p_cut) + 2.0 * dS * d1 + S * d2;
      return true;
    }
    if (r < r_reg) {
      double p, d1, d2;
      exact(r_reg, p, d1, d2);
      const double delta = r - r_reg;
      phi = p + d1 * delta + 0.5 * d2 * delta * delta;
      dphi = d1 + d2 * delta;
      d2phi = d2;
      return true;
    }
    exact(r, phi, dphi, d2phi);
    return true;
  }
};

}  // namespace spatula::contact
