// Adhesive friction at one point (adhesive_friction.hpp): stick and slip over a sweep of gaps in compression and
// tension with the traction on the sliding limit and the dissipation equal to limit x slip (the return mapping charges
// it at the mean of the committed and the end state's limits, the variational update at the end's); the sliding limits'
// values (extended Amontons zero at the strongest attraction, mu (T_n + t_max) elsewhere; off beyond the cut-off);
// the consistent tangent d t / d s and d t / d g against finite differences of the return mapping, in stick and in
// slip; and Newton on one point driven to a sliding state converging quadratically.
#include "contact/adhesive_friction.hpp"

#include <gtest/gtest.h>

#include <cmath>

using spatula::contact::AdhesiveFriction;
using spatula::contact::FrictionHistory;

namespace {

AdhesiveFriction amontons()
{
  AdhesiveFriction friction;
  friction.law.r_reg = 0.8 * friction.law.equilibrium_gap();
  friction.law.r_cut = 10.0;
  friction.limit = AdhesiveFriction::Limit::extended_amontons;
  friction.coefficient = 0.3;
  friction.stiffness = 20.0;
  friction.cutoff = 1.0;
  return friction;
}

AdhesiveFriction constant()
{
  auto friction = amontons();
  friction.limit = AdhesiveFriction::Limit::constant_strength;
  friction.strength = 0.05;
  return friction;
}

TEST(AdhesiveFriction, SlidingLimitsAreTheModelsOnes)
{
  const auto f = amontons();
  double tau, dtau, d2tau;
  f.sliding_limit(f.law.strongest_attraction_gap(), tau, dtau, d2tau);
  EXPECT_NEAR(tau, 0.0, 1e-12);   // at the strongest attraction no friction is left
  f.sliding_limit(f.law.equilibrium_gap(), tau, dtau, d2tau);
  EXPECT_NEAR(tau, 0.3 * f.law.max_traction(), 1e-12);   // T_n = 0: mu t_max, friction without pressure
  const double compressed = 0.9 * f.law.equilibrium_gap();
  double phi, dphi, d2phi;
  f.law.evaluate(compressed, phi, dphi, d2phi);
  f.sliding_limit(compressed, tau, dtau, d2tau);
  EXPECT_NEAR(tau, 0.3 * (-dphi + f.law.max_traction()), 1e-12);
  EXPECT_GT(tau, 0.3 * f.law.max_traction());
  f.sliding_limit(1.25 * f.cutoff, tau, dtau, d2tau);   // beyond the cut-off: none
  EXPECT_EQ(tau, 0.0);
  const auto c = constant();
  c.sliding_limit(0.5, tau, dtau, d2tau);
  EXPECT_DOUBLE_EQ(tau, 0.05);
  c.sliding_limit(1.1, tau, dtau, d2tau);
  EXPECT_GT(tau, 0.0);
  EXPECT_LT(tau, 0.05);
}

// Over gaps from compression to beyond the cut-off: a tangential travel s from the anchor at 0 sticks while
// eps_T |s| <= tau(g), with t = eps_T s; past it the traction sits on the limit along s, the anchor follows to
// s - t / eps_T, and the dissipation is tau x the anchor's travel.
TEST(AdhesiveFriction, StickThenSlipOnTheLimitWithItsDissipation)
{
  for (const auto& f : {amontons(), constant()}) {
    for (double g : {0.25, 0.3, 0.35, 0.4, 0.6, 0.9, 1.1, 1.3}) {
      double tau, dtau, d2tau;
      f.sliding_limit(g, tau, dtau, d2tau);
      const double onset = tau / f.stiffness;   // the travel at which slip begins
      const double direction[2] = {0.6, -0.8};
      FrictionHistory start;   // committed at this gap: the return mapping charges the slip at tau
      start.limit = tau;
      const double below[2] = {0.5 * onset * direction[0], 0.5 * onset * direction[1]};
      const auto stick = f.evaluate(g, below, start);
      EXPECT_FALSE(stick.sliding && tau > 0.0) << "gap " << g;
      if (tau > 0.0) {
        EXPECT_NEAR(stick.traction[0], f.stiffness * below[0], 1e-14);
        EXPECT_NEAR(stick.traction[1], f.stiffness * below[1], 1e-14);
        EXPECT_EQ(stick.trial.dissipated, 0.0);
      }
      const double travel = 2.0 * onset + 0.01;
      const double beyond[2] = {travel * direction[0], travel * direction[1]};
      const auto slip = f.evaluate(g, beyond, start);
      EXPECT_TRUE(slip.sliding) << "gap " << g;
      const double size = std::hypot(slip.traction[0], slip.traction[1]);
      EXPECT_NEAR(size, tau, 1e-13) << "gap " << g;
      EXPECT_NEAR(slip.traction[0] * direction[1] - slip.traction[1] * direction[0], 0.0, 1e-13);   // along s
      const double slipped = std::hypot(slip.trial.anchor[0], slip.trial.anchor[1]);
      EXPECT_NEAR(slipped, travel - onset, 1e-12) << "gap " << g;
      EXPECT_NEAR(slip.trial.dissipated, tau * (travel - onset), 1e-13) << "gap " << g;
      // Committed at a limit twice this one: the return mapping charges the slip at the mean, 1.5 tau; the
      // variational update at the end state's, tau.
      FrictionHistory stronger = start;
      stronger.limit = 2.0 * tau;
      auto variational = f;
      variational.variational = true;
      EXPECT_NEAR(f.evaluate(g, beyond, stronger).trial.dissipated, 1.5 * tau * (travel - onset), 1e-13) << g;
      EXPECT_NEAR(variational.evaluate(g, beyond, stronger).trial.dissipated, tau * (travel - onset), 1e-13) << g;
      // From the slid state, moving back by less than 2 onsets sticks again (the anchor holds).
      const double back[2] = {beyond[0] - onset * direction[0], beyond[1] - onset * direction[1]};
      const auto again = f.evaluate(g, back, slip.trial);
      EXPECT_FALSE(again.sliding && tau > 0.0) << "gap " << g;
    }
  }
}

// At the end of the cut-off's fade (1.25 g_c less one ulp, where 1 - t^3 (10 - 15 t + 6 t^2) rounds below zero) the
// limit is not negative, and a point on its anchor sticks: no 0/0 direction in its traction, anchor or dissipation.
TEST(AdhesiveFriction, AtTheEndOfTheFadeThePointOnItsAnchorSticksWithFiniteValues)
{
  for (const auto& f : {amontons(), constant()}) {
    const double g = std::nextafter(1.25 * f.cutoff, 0.0);
    double tau, dtau, d2tau;
    f.sliding_limit(g, tau, dtau, d2tau);
    EXPECT_GE(tau, 0.0);
    EXPECT_LT(tau, 1e-12);
    FrictionHistory start;
    start.anchor[0] = 0.3;
    start.anchor[1] = -0.2;
    start.limit = tau;
    const auto r = f.evaluate(g, start.anchor, start);
    EXPECT_FALSE(r.sliding);
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(r.traction[i], 0.0);
      EXPECT_EQ(r.trial.anchor[i], start.anchor[i]);
    }
    EXPECT_EQ(r.trial.dissipated, 0.0);
  }
}

// d t / d s and d t / d g against central differences of the return mapping (same history), in stick and in slip.
TEST(AdhesiveFriction, ConsistentTangentMatchesFiniteDifferences)
{
  for (const auto& f : {amontons(), constant()}) {
    FrictionHistory history;
    history.anchor[0] = 0.01;
    history.anchor[1] = -0.02;
    for (double g : {0.3, 0.35, 0.6, 1.1}) {
      double tau, dtau, d2tau;
      f.sliding_limit(g, tau, dtau, d2tau);
      for (double scale : {0.3, 3.0}) {   // stick, slip
        const double onset = tau / f.stiffness;
        const double s[2] = {history.anchor[0] + scale * onset * 0.8, history.anchor[1] + scale * onset * 0.6};
        const auto r = f.evaluate(g, s, history);
        const double h = 1e-5 * std::max(onset, 1e-6);   // (near the strongest attraction tau and the onset vanish)
        for (int j = 0; j < 2; ++j) {
          double plus[2] = {s[0], s[1]}, minus[2] = {s[0], s[1]};
          plus[j] += h;
          minus[j] -= h;
          const auto a = f.evaluate(g, plus, history), b = f.evaluate(g, minus, history);
          for (int i = 0; i < 2; ++i)
            EXPECT_NEAR(r.d_position[i][j], (a.traction[i] - b.traction[i]) / (2 * h), 1e-6 * f.stiffness)
                << "gap " << g << (r.sliding ? " slip" : " stick");
        }
        const auto a = f.evaluate(g + h, s, history), b = f.evaluate(g - h, s, history);
        for (int i = 0; i < 2; ++i)
          EXPECT_NEAR(r.d_gap[i], (a.traction[i] - b.traction[i]) / (2 * h), 1e-6 * std::max(1.0, std::abs(dtau)))
              << "gap " << g << (r.sliding ? " slip" : " stick");
      }
    }
  }
}

// One point on a tangential spring k to a driver at d, pulled past the sliding limit: the equilibrium
// k (d - s) = t(s) is found by Newton with the consistent tangent k + dt/ds, the residual falling quadratically.
TEST(AdhesiveFriction, NewtonInSlipConvergesQuadratically)
{
  const auto f = amontons();
  const double g = 0.35, k = 5.0;
  double tau, dtau, d2tau;
  f.sliding_limit(g, tau, dtau, d2tau);
  const double driver[2] = {3.0 * tau / k + 0.2, 0.1};   // far enough that the point slides
  FrictionHistory history;   // an anchor off the driver's line: the sliding direction turns as s moves
  history.anchor[0] = -0.5 * tau / f.stiffness;
  history.anchor[1] = 2.0 * tau / f.stiffness;
  double s[2] = {0.0, 0.0};
  double previous = 0.0;
  int quadratic = 0, iterations = 0;
  for (; iterations < 20; ++iterations) {
    const auto r = f.evaluate(g, s, history);
    const double residual[2] = {r.traction[0] - k * (driver[0] - s[0]), r.traction[1] - k * (driver[1] - s[1])};
    const double norm = std::hypot(residual[0], residual[1]);
    if (norm < 1e-13) break;
    if (previous > 0.0 && previous < 1e-2 && norm < 10.0 * previous * previous) ++quadratic;
    previous = norm;
    const double J[2][2] = {{r.d_position[0][0] + k, r.d_position[0][1]}, {r.d_position[1][0], r.d_position[1][1] + k}};
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    s[0] -= (J[1][1] * residual[0] - J[0][1] * residual[1]) / det;
    s[1] -= (-J[1][0] * residual[0] + J[0][0] * residual[1]) / det;
  }
  const auto r = f.evaluate(g, s, history);
  EXPECT_TRUE(r.sliding);
  EXPECT_NEAR(std::hypot(r.traction[0], r.traction[1]), tau, 1e-12);
  EXPECT_NEAR(r.traction[0], k * (driver[0] - s[0]), 1e-12);
  EXPECT_LE(iterations, 8);
  EXPECT_GE(quadratic, 1) << "no quadratic step seen in " << iterations << " iterations";
}

}  // namespace
