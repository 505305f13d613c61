// Adhesive friction on contact faces (friction_integrand.hpp through contact_face.hpp): the residual and the
// non-symmetric tangent against finite differences with some points sticking and some sliding (Q1C1 and Q1C2);
// a face slid along the substrate at the equilibrium gap through stick, slip and stick again, its force and its
// dissipated energy against the exact values; and the history: trial histories from the face, the start (no
// history) traction-free.
#include "contact/friction_integrand.hpp"

#include "skewed_face.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

using namespace spatula;

namespace {

contact::AdhesiveFrictionIntegrand integrand(contact::AdhesiveFriction::Limit limit)
{
  contact::LennardJones lj;
  lj.r_reg = 0.8 * lj.equilibrium_gap();
  lj.r_cut = 5.0;
  contact::AdhesiveFriction friction;
  friction.law = lj;
  friction.limit = limit;
  friction.coefficient = 0.3;
  friction.strength = 0.02;   // nN/nm^2
  friction.stiffness = 5.0;   // nN/nm^3
  friction.cutoff = 0.5;   // nm: the lifted corner of the face below reaches the switch-off band
  return {{lj, {-lj.equilibrium_gap()}}, friction};
}

// A 6 nm x 5 nm face on Z = 0 (slightly skewed), lifted unevenly by up to 0.5 nm and slid by a few hundredths of
// a nm: some points stick, some slide against the history below.
template <class Surface>
void face_state(double X[Surface::nodes][3], double u[Surface::nodes][3])
{
  test::skewed_face<Surface>(X);
  for (int k = 0; k < Surface::nodes; ++k) {
    const double s = test::face_node_parameters[k][0], t = test::face_node_parameters[k][1];
    u[k][0] = 0.01 + 0.004 * (s + 1.0) + 0.002 * std::sin(1.0 + k);
    u[k][1] = -0.003 * (t + 1.0) + 0.001 * std::cos(2.0 * k);
    u[k][2] = 0.25 * (s + 1.0) + 0.05 * std::sin(3.0 * k) - 0.02;
  }
}

// The face of face_state() from a history that leaves some points sticking and some sliding, against central
// differences (step h) at the same history in: the residual against the energy, the tangent against the residual,
// each relative to its largest entry, and the tangent's largest asymmetry relative to its largest entry.
struct FaceCheck {
  double residual = 0.0, tangent = 0.0, asymmetry = 0.0;
  int sliding = 0, sticking = 0;
};

template <class Surface>
FaceCheck check_face(const contact::AdhesiveFrictionIntegrand& law, double h)
{
  constexpr int n = Surface::nodes, dofs = 3 * n, order = 4, kept = contact::AdhesiveFrictionIntegrand::history_size;
  double X[n][3], u[n][3], r[dofs], K[dofs][dofs];
  face_state<Surface>(X, u);
  std::vector<double> history(order * order * kept, 0.0), trial(order * order * kept);
  for (int p = 0; p < order * order; ++p) {   // anchors scattered around the travel: some points beyond the limit
    history[p * kept] = 0.012 + 0.006 * std::sin(1.7 * p);
    history[p * kept + 1] = -0.002 + 0.004 * std::cos(2.3 * p);
  }
  contact::contact_face<Surface>(law, X, X, u, order, r, K, history.data(), trial.data());
  FaceCheck check;
  for (int p = 0; p < order * order; ++p) {
    const bool moved = trial[p * kept] != history[p * kept] || trial[p * kept + 1] != history[p * kept + 1];
    (moved ? check.sliding : check.sticking) += 1;
  }
  double largest_r = 0.0, largest_K = 0.0;
  for (int q = 0; q < dofs; ++q) {
    double up[n][3], um[n][3], rp[dofs], rm[dofs];
    std::copy(&u[0][0], &u[0][0] + dofs, &up[0][0]);
    std::copy(&u[0][0], &u[0][0] + dofs, &um[0][0]);
    up[q / 3][q % 3] += h;
    um[q / 3][q % 3] -= h;
    const auto plus = contact::contact_face<Surface>(law, X, X, up, order, rp, nullptr, history.data());
    const auto minus = contact::contact_face<Surface>(law, X, X, um, order, rm, nullptr, history.data());
    check.residual = std::max(check.residual, std::abs((plus.energy - minus.energy) / (2 * h) - r[q]));
    largest_r = std::max(largest_r, std::abs(r[q]));
    for (int p = 0; p < dofs; ++p) {
      check.tangent = std::max(check.tangent, std::abs((rp[p] - rm[p]) / (2 * h) - K[p][q]));
      largest_K = std::max(largest_K, std::abs(K[p][q]));
      check.asymmetry = std::max(check.asymmetry, std::abs(K[p][q] - K[q][p]));
    }
  }
  check.residual /= largest_r;
  check.tangent /= largest_K;
  check.asymmetry /= largest_K;
  return check;
}

// The return mapping: the tangent is the derivative of the residual, and not symmetric.
template <class Surface>
void expect_consistent(const contact::AdhesiveFrictionIntegrand& law)
{
  const auto check = check_face<Surface>(law, 1e-7);
  EXPECT_GT(check.sliding, 0);
  EXPECT_GT(check.sticking, 0);
  EXPECT_LT(check.tangent, 1e-6);
  EXPECT_GT(check.asymmetry, 1e-4);   // slip couples the tangential traction to the gap, not the reverse
}

// The variational update: the residual is the derivative of the energy and the tangent that of the residual, and
// it is symmetric, with points sticking and sliding.
template <class Surface>
void expect_variational(const contact::AdhesiveFrictionIntegrand& law)
{
  const auto check = check_face<Surface>(law, 1e-6);
  EXPECT_GT(check.sliding, 0);
  EXPECT_GT(check.sticking, 0);
  EXPECT_LT(check.residual, 1e-6);
  EXPECT_LT(check.tangent, 1e-5);
  EXPECT_LT(check.asymmetry, 1e-12);
}

// A flat face at the equilibrium gap slid uniformly along X by `slide` from the history `in`: its X force.
double slid_face_force(const contact::AdhesiveFrictionIntegrand& law, double slide, const std::vector<double>& in,
                       std::vector<double>& out, double& dissipated, double lift = 0.0)
{
  using Surface = elements::Quad9Surface;
  double X[9][3], u[9][3], r[27];
  for (int k = 0; k < 9; ++k) {
    X[k][0] = 2.0 * (test::face_node_parameters[k][0] + 1.0);   // 4 nm x 3 nm
    X[k][1] = 1.5 * (test::face_node_parameters[k][1] + 1.0);
    X[k][2] = 0.0;
    u[k][0] = slide;
    u[k][1] = 0.0;
    u[k][2] = lift;
  }
  const auto result = contact::contact_face<Surface>(law, X, X, u, 3, r, nullptr, in.data(), out.data());
  dissipated = result.dissipated;
  double force = 0.0;
  for (int k = 0; k < 9; ++k) force += r[3 * k];
  return force;
}

void expect_stick_slip_stick(const contact::AdhesiveFrictionIntegrand& law, double tau)
{
  const double area = 12.0, stiffness = law.friction.stiffness, onset = tau / stiffness;   // slip starts at tau / eps
  constexpr int kept = contact::AdhesiveFrictionIntegrand::history_size;
  std::vector<double> committed(9 * kept, 0.0), trial(9 * kept);
  double dissipated;
  // Stick: the elastic spring.
  EXPECT_NEAR(slid_face_force(law, 0.5 * onset, committed, trial, dissipated), stiffness * 0.5 * onset * area,
              1e-12 * tau * area);
  EXPECT_EQ(dissipated, 0.0);
  // Slip, reached in two converged states: the force on the limit, the energy dissipated = limit x slip.
  slid_face_force(law, 2.0 * onset, committed, trial, dissipated);
  committed = trial;
  EXPECT_NEAR(slid_face_force(law, 3.0 * onset, committed, trial, dissipated), tau * area, 1e-12 * tau * area);
  EXPECT_NEAR(dissipated, tau * area * 2.0 * onset, 1e-12 * tau * area * onset);
  committed = trial;
  // Back by less than twice the elastic range: stick again, the force falling with the spring's stiffness.
  EXPECT_NEAR(slid_face_force(law, 2.5 * onset, committed, trial, dissipated), tau * area - stiffness * 0.5 * onset * area,
              1e-12 * tau * area);
  EXPECT_NEAR(dissipated, tau * area * 2.0 * onset, 1e-12 * tau * area * onset);
  // And on back to the opposite limit.
  EXPECT_NEAR(slid_face_force(law, 0.0, committed, trial, dissipated), -tau * area, 1e-12 * tau * area);
}

}  // namespace

TEST(FrictionFace, TangentsMatchFiniteDifferencesInStickAndSlip)
{
  for (auto limit : {contact::AdhesiveFriction::Limit::extended_amontons,
                     contact::AdhesiveFriction::Limit::constant_strength}) {
    const auto law = integrand(limit);
    expect_consistent<elements::Quad4Surface>(law);
    expect_consistent<elements::Quad9Surface>(law);
  }
}

TEST(FrictionFace, TheVariationalUpdateIsTheDerivativeOfItsEnergyWithASymmetricTangent)
{
  for (auto limit : {contact::AdhesiveFriction::Limit::extended_amontons,
                     contact::AdhesiveFriction::Limit::constant_strength}) {
    auto law = integrand(limit);
    law.friction.variational = true;
    EXPECT_TRUE(contact::symmetric_tangent(law));
    expect_variational<elements::Quad4Surface>(law);
    expect_variational<elements::Quad9Surface>(law);
  }
  EXPECT_FALSE(contact::symmetric_tangent(integrand(contact::AdhesiveFriction::Limit::extended_amontons)));
}

// The frozen limit: the variational energy with each point sliding on the limit its history holds (here that of the
// equilibrium gap, set by the first evaluation from the anchors), so the traction does not depend on the gap in slip.
TEST(FrictionFace, TheFrozenLimitIsTheDerivativeOfItsEnergyWithoutNormalCoupling)
{
  for (auto limit : {contact::AdhesiveFriction::Limit::extended_amontons,
                     contact::AdhesiveFriction::Limit::constant_strength}) {
    auto law = integrand(limit);
    law.friction.variational = law.friction.frozen = true;
    EXPECT_TRUE(contact::symmetric_tangent(law));
    expect_variational<elements::Quad4Surface>(law);
    expect_variational<elements::Quad9Surface>(law);
  }
}

TEST(FrictionFace, ConstantStrengthSlidesAtTheStrengthTimesTheArea)
{
  const auto law = integrand(contact::AdhesiveFriction::Limit::constant_strength);
  expect_stick_slip_stick(law, law.friction.strength);
}

// At the equilibrium gap the normal traction is zero, so the extended Amontons limit is mu t_max.
TEST(FrictionFace, ExtendedAmontonsAtTheEquilibriumGapSlidesAtMuTimesTheStrongestAttraction)
{
  const auto law = integrand(contact::AdhesiveFriction::Limit::extended_amontons);
  expect_stick_slip_stick(law, law.friction.coefficient * law.friction.law.max_traction());
}

// Without a history the face starts from its undeformed anchors: no tangential force; with one it carries the
// frictionless law's normal force and energy, and the friction's elastic energy in stick.
TEST(FrictionFace, UndeformedStartIsTractionFreeAndStickStoresTheSpringEnergy)
{
  const auto law = integrand(contact::AdhesiveFriction::Limit::constant_strength);
  constexpr int kept = contact::AdhesiveFrictionIntegrand::history_size;
  std::vector<double> none(9 * kept, 0.0), trial(9 * kept);
  double dissipated;
  EXPECT_NEAR(slid_face_force(law, 0.0, none, trial, dissipated), 0.0, 1e-14);
  double X[9][3] = {}, u[9][3] = {}, r_friction[27], r_frictionless[27];
  const double slide = 0.3 * law.friction.strength / law.friction.stiffness;
  for (int k = 0; k < 9; ++k) {
    X[k][0] = 2.0 * (test::face_node_parameters[k][0] + 1.0);
    X[k][1] = 1.5 * (test::face_node_parameters[k][1] + 1.0);
    u[k][0] = slide;
    u[k][2] = 0.1 * test::face_node_parameters[k][0];
  }
  const auto with = contact::contact_face<elements::Quad9Surface>(law, X, X, u, 3, r_friction);
  const auto without = contact::contact_face<elements::Quad9Surface>(law.normal, X, X, u, 3, r_frictionless);
  EXPECT_NEAR(with.energy - without.energy, 0.5 * law.friction.stiffness * slide * slide * with.area,
              1e-12 * std::abs(without.energy));
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(r_friction[3 * k + 2], r_frictionless[3 * k + 2], 1e-14);
}

// The frozen limit: a face sliding on the limit of its committed state (the equilibrium gap), then lifted so that its
// limit falls, still slides on the committed limit in that step; committed there, its spring's energy above the new
// limit is dissipated, so the state's energy and dissipation are those the next step starts from.
TEST(FrictionFace, TheFrozenLimitLetsTheSpringAboveAFallenLimitGoAsDissipation)
{
  auto law = integrand(contact::AdhesiveFriction::Limit::extended_amontons);
  law.friction.variational = law.friction.frozen = true;
  constexpr int kept = contact::AdhesiveFrictionIntegrand::history_size;
  const double area = 12.0, stiffness = law.friction.stiffness;
  double high, dtau, d2tau, low;
  law.friction.sliding_limit(law.normal.gap(std::array<double, 3>{0.0, 0.0, 0.0}.data()), high, dtau, d2tau);
  const double lift = 0.02;   // towards the strongest attraction: the limit falls
  law.friction.sliding_limit(law.normal.gap(std::array<double, 3>{0.0, 0.0, lift}.data()), low, dtau, d2tau);
  ASSERT_LT(low, 0.9 * high);
  std::vector<double> committed(9 * kept, 0.0), trial(9 * kept);
  double dissipated;
  const double slide = 3.0 * high / stiffness;
  slid_face_force(law, slide, committed, trial, dissipated);   // sliding on the limit at the equilibrium gap
  committed = trial;
  const double before = dissipated;
  // Lifted in the next step: the step slides on the committed limit ...
  EXPECT_NEAR(slid_face_force(law, slide, committed, trial, dissipated, lift), high * area, 1e-9 * high * area);
  EXPECT_NEAR(dissipated - before, 0.5 * (high * high - low * low) / stiffness * area, 1e-9 * high * high * area);
  // ... and committed there, the state holds the spring at the new limit, sticking, with nothing more dissipated.
  committed = trial;
  const double after = dissipated;
  EXPECT_NEAR(slid_face_force(law, slide, committed, trial, dissipated, lift), low * area, 1e-9 * high * area);
  EXPECT_NEAR(dissipated, after, 1e-12 * high * area);
}
