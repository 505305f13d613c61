#pragma once
// Adhesive friction at one contact point: the tangential traction of a sliding law that acts in tension as well as
// in compression (Mergel, Sahli, Scheibert and Sauer, J. Adhesion 2019), as a pure function of the gap, the point's
// tangential position and its history (deal.II's quadrature-point history: the state comes in, the trial state goes
// out, and the caller commits it only at a converged state).
//
// Elastic stick, then slip on a sliding limit tau(g) (a return mapping, exact for this one-surface model):
//   trial traction  t* = eps_T (s - a),    s: the point's tangential position, a: its sliding anchor (the history),
//   stick (|t*| <= tau(g)):  t = t*,                          a unchanged,
//   slip  (|t*| >  tau(g)):  t = tau(g) n,  n = t* / |t*|,     a = s - t / eps_T,
// and the energy dissipated in the slip, |a_new - a_old| charged at a limit (the elastic part eps_T |s - a|^2 / 2 is
// stored): at tau(g) under the variational updates (whose energy is the step's potential), at the mean
// (tau_0 + tau(g)) / 2 under the return mapping, tau_0 the limit at the committed state (the trapezoidal rule the
// work of the reactions is integrated by: its energy balance is second order in the step).
// The history also keeps tau at its state; with `frozen` a step slides on that limit of the committed state instead
// of tau(g) (an explicit limit: the step's energy does not depend on g through it).
// The sliding limits (`Limit`):
//   extended Amontons:   tau = mu (T_n(g) + t_max) C(g), T_n = -phi'(g) the Lennard-Jones normal traction (positive in
//                        compression), t_max its strongest attraction: zero where the attraction is strongest, growing
//                        with compression, positive in tension;
//   constant strength:   tau = tau_0 C(g);
// both switched off beyond the cut-off gap g_c by C = 1 up to g_c, the quintic smootherstep down to 0 at 1.25 g_c
// (C1 and C2 continuous: a hard cut would make the residual jump).
// The consistent tangent: d t / d s (2 x 2) and d t / d g (2: the normal-tangential coupling, zero in stick); the
// normal traction does not depend on s, so the point's tangent is not symmetric in slip.
#include "contact/lennard_jones.hpp"

#include <Kokkos_Core.hpp>

#include <cmath>

namespace spatula::contact {

struct FrictionHistory {
  double anchor[2] = {0.0, 0.0};   // where the tangential spring is relaxed [nm]
  double dissipated = 0.0;         // energy dissipated by sliding so far, per unit area [nN/nm]
  double limit = 0.0;              // tau at this state [nN/nm^2]: with `frozen`, the committed one is a step's limit
};

struct FrictionResponse {
  double traction[2] = {0.0, 0.0};   // t, on the point along the substrate [nN/nm^2]
  double d_position[2][2] = {{0.0, 0.0}, {0.0, 0.0}};   // d t_i / d s_j
  double d_gap[2] = {0.0, 0.0};                          // d t_i / d g
  bool sliding = false;
  double limit = 0.0;                // tau(g)
  double charged = 0.0;              // the limit the step's slip is charged at (see above)
  double limit_slope = 0.0, limit_curvature = 0.0;   // tau'(g), tau''(g)
  FrictionHistory trial;             // the history after this state (commit it at a converged state)
};

struct AdhesiveFriction {
  enum class Limit { extended_amontons, constant_strength };
  LennardJones law;            // the normal law whose traction the extended Amontons limit follows
  Limit limit = Limit::extended_amontons;
  double coefficient = 0.3;    // mu (extended Amontons)
  double strength = 0.0;       // tau_0 [nN/nm^2] (constant strength)
  double stiffness = 10.0;     // eps_T [nN/nm^3], the elastic stick's tangential stiffness per unit area
  double cutoff = 1.0;         // g_c [nm]
  bool variational = false;    // the contact integrand's update (friction_integrand.hpp): false the return mapping
  bool frozen = false;         // (with variational) a step slides on the limit of its committed state, not of its gap

  // C(g), C'(g) and C''(g): 1 up to g_c, smootherstep to 0 at 1.25 g_c.
  KOKKOS_INLINE_FUNCTION void switch_off(double g, double& c, double& dc, double& d2c) const
  {
    const double width = 0.25 * cutoff;
    if (g <= cutoff) {
      c = 1.0;
      dc = d2c = 0.0;
      return;
    }
    if (g >= cutoff + width) {
      c = dc = d2c = 0.0;
      return;
    }
    const double t = (g - cutoff) / width, u = 1.0 - t;
    c = u * u * u * (1.0 + 3.0 * t + 6.0 * t * t);   // 1 - t^3 (10 - 15 t + 6 t^2), never below zero near t = 1
    dc = -30.0 * t * t * u * u / width;
    d2c = -60.0 * t * u * (1.0 - 2.0 * t) / (width * width);
  }

  // tau(g), tau'(g) and tau''(g).
  KOKKOS_INLINE_FUNCTION void sliding_limit(double g, double& tau, double& dtau, double& d2tau) const
  {
    double c, dc, d2c;
    switch_off(g, c, dc, d2c);
    if (limit == Limit::constant_strength) {
      tau = strength * c;
      dtau = strength * dc;
      d2tau = strength * d2c;
      return;
    }
    double phi, dphi, d2phi;
    law.evaluate(g, phi, dphi, d2phi);
    const double lifted = -dphi + law.max_traction();   // T_n + t_max >= 0
    const bool positive = lifted > 0.0;
    const double part = positive ? lifted : 0.0, slope = positive ? -d2phi : 0.0;
    const double curvature = positive && c > 0.0 ? -law.third_derivative(g) : 0.0;
    tau = coefficient * part * c;
    dtau = coefficient * (slope * c + part * dc);
    d2tau = coefficient * (curvature * c + 2.0 * slope * dc + part * d2c);
  }

  // The response at gap g and tangential position s from the history `in`.
  KOKKOS_INLINE_FUNCTION FrictionResponse evaluate(double g, const double s[2], const FrictionHistory& in) const
  {
    FrictionResponse out;
    out.trial = in;
    double tau, dtau;
    sliding_limit(g, tau, dtau, out.limit_curvature);
    out.trial.limit = tau;
    if (frozen) {   // the step's limit does not depend on its gap: no normal-tangential coupling
      tau = in.limit;
      dtau = out.limit_curvature = 0.0;
    }
    out.limit = tau;
    out.limit_slope = dtau;
    out.charged = variational ? tau : 0.5 * (in.limit + tau);
    const double trial[2] = {stiffness * (s[0] - in.anchor[0]), stiffness * (s[1] - in.anchor[1])};
    const double size = ::sqrt(trial[0] * trial[0] + trial[1] * trial[1]);
    if (size <= tau || size == 0.0) {   // stick (a point on its anchor sticks, whatever its limit)
      for (int i = 0; i < 2; ++i) {
        out.traction[i] = trial[i];
        out.d_position[i][i] = stiffness;
      }
      return out;
    }
    out.sliding = true;   // slip: back to the limit along the trial direction
    const double n[2] = {trial[0] / size, trial[1] / size};
    double slipped = 0.0;
    for (int i = 0; i < 2; ++i) {
      out.traction[i] = tau * n[i];
      out.d_gap[i] = dtau * n[i];
      for (int j = 0; j < 2; ++j) out.d_position[i][j] = tau / size * stiffness * ((i == j ? 1.0 : 0.0) - n[i] * n[j]);
      out.trial.anchor[i] = s[i] - out.traction[i] / stiffness;
      const double step = out.trial.anchor[i] - in.anchor[i];
      slipped += step * step;
    }
    out.trial.dissipated = in.dissipated + out.charged * ::sqrt(slipped);
    return out;
  }
};

}  // namespace spatula::contact
