#pragma once
// Adhesive friction on a flat substrate as a contact face integrand: the frictionless Lennard-Jones law along the
// normal and the sliding law of adhesive_friction.hpp along the substrate, with a history at each quadrature point.
//
// The point's tangential travel s = (x - A)_{X,Y} is measured from its anchor A (its reference position unless a run
// re-anchored the faces); its history holds the sliding anchor a relative to A (2 values, zero at the start: the
// undeformed pad is traction-free) and the energy dissipated there per unit area (1 value). The gradient is
// (t_X, t_Y, phi'(g)), g = z - h; the Hessian is d t / d s, d t / d g and phi''(g): not symmetric in slip (the sliding
// limit depends on g, the normal traction not on s).
//
// The energy density is phi(g) plus the friction's incremental potential psi with the sliding limit tau = tau(g),
//   stick: eps_T |s - a|^2 / 2,   slip: tau |s - a| - tau^2 / (2 eps_T),
// whose derivative along s is the traction t. The return mapping (AdhesiveFriction::variational false) leaves out its
// derivative along g, tau'(g) (|s - a| - tau / eps_T) in slip: the gradient is not that of the energy and the tangent
// is not symmetric; its energy charges the slip |s - a| - tau / eps_T at the limit the law's dissipation does,
// (tau_0 + tau) / 2 instead of tau, tau_0 the limit at the committed state (adhesive_friction.hpp).
// The variational update (true: Ortiz and Stainier's variational constitutive updates) takes the whole derivative of
// psi: the normal traction gains tau' times the step's slip (which vanishes with the step),
// the energy is the step's potential and the tangent is symmetric (tau'' included), so the energy line search, the
// jumps' descents and LDL^T factors see a consistent problem. With the extended Amontons limit its normal term
// tau' times the slip pulls a sliding point towards the strongest attraction (docs/adhesion.md). The frozen update
// (AdhesiveFriction::frozen, with variational) slides a step on the limit of the committed state: the same energy
// without that term, a symmetric tangent without the coupling. Without a history (the front diagnostics'
// five-argument evaluate) the integrand is the normal law alone.
#include "contact/adhesive_friction.hpp"
#include "contact/contact_face.hpp"

namespace spatula::contact {

struct AdhesiveFrictionIntegrand {
  FrictionlessIntegrand<FlatSubstrate> normal;
  AdhesiveFriction friction;
  // sliding anchor (X, Y) relative to A [nm], dissipated [nN/nm], 1 + the limit tau at the state [nN/nm^2] (0: no
  // state committed yet, nor kept by a checkpoint written before this value was: the limit at the anchors' gap)
  static constexpr int history_size = 4;
  static constexpr int dissipated_index = 2;
  static constexpr bool tangential = true;   // holds the pad along the substrate
  KOKKOS_INLINE_FUNCTION bool symmetric_tangent() const { return friction.variational; }
  // The integrand a jump's energy descent minimizes: the return mapping's gradient is not that of an energy (nor its
  // tangent symmetric), so its descents take the frozen limit's, on the same history; the variational updates their
  // own.
  bool descends_on_another_energy() const { return !friction.variational; }
  AdhesiveFrictionIntegrand descent_integrand() const
  {
    AdhesiveFrictionIntegrand frozen = *this;
    frozen.friction.variational = frozen.friction.frozen = true;
    return frozen;
  }
  KOKKOS_INLINE_FUNCTION static double dissipated(const double* history) { return history[dissipated_index]; }

  KOKKOS_INLINE_FUNCTION double far_bound(const double x[3]) const { return normal.far_bound(x); }
  // Beyond both the normal law's cut-off and the friction's (where the sliding limit is zero).
  KOKKOS_INLINE_FUNCTION double cut_off() const
  {
    const double friction_end = 1.25 * friction.cutoff;
    return normal.cut_off() > friction_end ? normal.cut_off() : friction_end;
  }
  KOKKOS_INLINE_FUNCTION double gap(const double x[3]) const { return normal.gap(x); }
  KOKKOS_INLINE_FUNCTION double inflection() const { return normal.inflection(); }
  KOKKOS_INLINE_FUNCTION double range() const { return normal.range(); }

  // The normal law alone.
  KOKKOS_INLINE_FUNCTION bool evaluate(const double A[3], const double x[3], double& phi, double gradient[3],
                                       double (*H)[3]) const
  {
    return normal.evaluate(A, x, phi, gradient, H);
  }

  // With the point's history `in` (history_size values); writes the trial history to `out`.
  KOKKOS_INLINE_FUNCTION bool evaluate(const double A[3], const double x[3], const double* in, double* out,
                                       double& phi, double gradient[3], double (*H)[3]) const
  {
    const bool normal_active = normal.evaluate(A, x, phi, gradient, H);
    const double g = normal.gap(x);
    const double s[2] = {x[0] - A[0], x[1] - A[1]};
    FrictionHistory history;
    history.anchor[0] = in[0];
    history.anchor[1] = in[1];
    history.dissipated = in[2];
    if (in[3] > 0.0) {
      history.limit = in[3] - 1.0;
    } else if (friction.frozen || !friction.variational) {   // the anchors' state is the committed one (the undeformed
                                                               // or the re-anchored pad)
      double tau, dtau, d2tau;
      friction.sliding_limit(normal.gap(A), tau, dtau, d2tau);
      history.limit = tau;
    }
    const FrictionResponse response = friction.evaluate(g, s, history);
    out[0] = response.trial.anchor[0];
    out[1] = response.trial.anchor[1];
    out[2] = response.trial.dissipated;
    out[3] = 1.0 + response.trial.limit;
    if (friction.frozen) {   // the next step slides on this state's limit: the spring's energy above it is dissipated
      const double t2 = response.traction[0] * response.traction[0] + response.traction[1] * response.traction[1];
      const double limit = response.trial.limit;
      if (t2 > limit * limit) {
        const double scale = limit / ::sqrt(t2);
        for (int i = 0; i < 2; ++i) out[i] = s[i] - scale * response.traction[i] / friction.stiffness;
        out[2] += 0.5 * (t2 - limit * limit) / friction.stiffness;
      }
    }
    const double tau = response.limit, stiffness = friction.stiffness;
    const double travel = ::sqrt((s[0] - in[0]) * (s[0] - in[0]) + (s[1] - in[1]) * (s[1] - in[1]));
    const double slip = travel - tau / stiffness;   // |a - a_in|, charged at the law's limit for it
    phi += response.sliding ? response.charged * slip + 0.5 * tau * tau / stiffness : 0.5 * stiffness * travel * travel;
    for (int i = 0; i < 2; ++i) gradient[i] += response.traction[i];
    if (H)
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) H[i][j] += response.d_position[i][j];
        H[i][2] += response.d_gap[i];
      }
    if (friction.variational && response.sliding) {   // d psi / d g = tau' (|s - a| - tau / eps_T)
      const double slope = response.limit_slope;
      gradient[2] += slope * slip;
      if (H) {
        for (int i = 0; i < 2; ++i) H[2][i] += response.d_gap[i];
        H[2][2] += response.limit_curvature * slip - slope * slope / stiffness;
      }
    }
    return normal_active || tau > 0.0 || response.traction[0] != 0.0 || response.traction[1] != 0.0;
  }
};

}  // namespace spatula::contact
