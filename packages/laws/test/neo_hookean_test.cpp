// The Neo-Hookean law: zero stress at F = I, stress and tangent against finite differences of the energy,
// frame invariance, the small-strain limit, and rejection of inverted states.
#include "laws/neo_hookean.hpp"

#include <gtest/gtest.h>

#include <cmath>

using spatula::laws::NeoHookean;

namespace {

const NeoHookean law = NeoHookean::from_young(2.0, 0.2);   // E = 2 GPa, nu = 0.2 (the paper's)
const double F0[3][3] = {{1.10, 0.15, -0.05}, {-0.08, 0.92, 0.12}, {0.06, -0.11, 1.05}};

double energy_of(const double F[3][3])
{
  double W = 0.0, P[3][3];
  EXPECT_TRUE(law.evaluate(F, W, P));
  return W;
}

void rotation(double angle, const double axis_in[3], double R[3][3])
{
  const double n = std::sqrt(axis_in[0] * axis_in[0] + axis_in[1] * axis_in[1] + axis_in[2] * axis_in[2]);
  const double a[3] = {axis_in[0] / n, axis_in[1] / n, axis_in[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  const double K[3][3] = {{0, -a[2], a[1]}, {a[2], 0, -a[0]}, {-a[1], a[0], 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + s * K[i][j] + (1 - c) * a[i] * a[j];
}

}  // namespace

TEST(NeoHookean, LameParameters)
{
  EXPECT_NEAR(law.mu, 2.0 / 2.4, 1e-15);
  EXPECT_NEAR(law.lambda, 2.0 * law.mu * 0.2 / 0.6, 1e-15);
}

TEST(NeoHookean, ZeroEnergyAndStressAtIdentity)
{
  const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double W, P[3][3];
  ASSERT_TRUE(law.evaluate(I, W, P));
  EXPECT_EQ(W, 0.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(P[i][j], 0.0, 1e-15);
}

TEST(NeoHookean, StressIsTheEnergyDerivative)
{
  double W, P[3][3];
  ASSERT_TRUE(law.evaluate(F0, W, P));
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double Fp[3][3], Fm[3][3];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) Fp[a][b] = Fm[a][b] = F0[a][b];
      Fp[i][j] += h;
      Fm[i][j] -= h;
      const double derivative = (energy_of(Fp) - energy_of(Fm)) / (2 * h);
      EXPECT_NEAR(derivative, P[i][j], 1e-6 * std::max(1.0, std::abs(P[i][j])));
    }
}

TEST(NeoHookean, TangentIsTheStressDerivative)
{
  double W, P[3][3], A[9][9];
  ASSERT_TRUE(law.evaluate(F0, W, P, A));
  const double h = 1e-6;
  double largest = 0.0, worst = 0.0;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      double Fp[3][3], Fm[3][3], Pp[3][3] = {}, Pm[3][3] = {}, Wp, Wm;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) Fp[a][b] = Fm[a][b] = F0[a][b];
      Fp[k][l] += h;
      Fm[k][l] -= h;
      law.evaluate(Fp, Wp, Pp);
      law.evaluate(Fm, Wm, Pm);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double derivative = (Pp[i][j] - Pm[i][j]) / (2 * h);
          largest = std::max(largest, std::abs(A[3 * i + j][3 * k + l]));
          worst = std::max(worst, std::abs(derivative - A[3 * i + j][3 * k + l]));
        }
    }
  EXPECT_LT(worst / largest, 1e-6);
  // Major symmetry A_iJkL = A_kLiJ (hyperelastic).
  for (int p = 0; p < 9; ++p)
    for (int q = 0; q < 9; ++q) EXPECT_NEAR(A[p][q], A[q][p], 1e-12);
}

TEST(NeoHookean, FrameInvariance)
{
  const double axis[3] = {0.3, -0.7, 0.5};
  double Q[3][3];
  rotation(0.83, axis, Q);
  double QF[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      QF[i][j] = 0.0;
      for (int k = 0; k < 3; ++k) QF[i][j] += Q[i][k] * F0[k][j];
    }
  double W, P[3][3], WQ, PQ[3][3];
  law.evaluate(F0, W, P);
  law.evaluate(QF, WQ, PQ);
  EXPECT_NEAR(WQ, W, 1e-14);
  for (int i = 0; i < 3; ++i)   // P(QF) = Q P(F)
    for (int j = 0; j < 3; ++j) {
      double QP = 0.0;
      for (int k = 0; k < 3; ++k) QP += Q[i][k] * P[k][j];
      EXPECT_NEAR(PQ[i][j], QP, 1e-13);
    }
  // A pure rotation stores no energy and has zero Cauchy stress.
  double sigma[3][3];
  ASSERT_TRUE(law.cauchy(Q, sigma));
  EXPECT_NEAR(energy_of(Q), 0.0, 1e-14);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(sigma[i][j], 0.0, 1e-14);
}

TEST(NeoHookean, SmallStrainLimitIsHookesLaw)
{
  const double e = 1e-7;   // uniaxial stretch: sigma_xx = (lambda + 2 mu) e, sigma_yy = lambda e
  const double F[3][3] = {{1 + e, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double sigma[3][3];
  ASSERT_TRUE(law.cauchy(F, sigma));
  EXPECT_NEAR(sigma[0][0] / e, law.lambda + 2 * law.mu, 1e-5);
  EXPECT_NEAR(sigma[1][1] / e, law.lambda, 1e-5);
}

TEST(NeoHookean, InvertedStatesAreRejected)
{
  const double inverted[3][3] = {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const double flat[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 0}};
  double W = 123.0, P[3][3];
  EXPECT_FALSE(law.evaluate(inverted, W, P));
  EXPECT_FALSE(law.evaluate(flat, W, P));
  EXPECT_EQ(W, 123.0);
}
