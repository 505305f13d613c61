// The adhesion laws: Lennard-Jones values against the closed forms of the paper's Sec. 3 (eqs. 16, 22, 23), its
// derivatives, regularization and cut-off; stiction reducing to the frictionless law; rough-substrate projection
// against a brute-force search and its curvature terms against finite differences.
#include "contact/contact_face.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatula;
using contact::LennardJones;

namespace {

constexpr double pi = 3.14159265358979323846;

LennardJones base_law()   // A_H = 1e-19 J, r0 = 0.4 nm
{
  LennardJones law;
  law.hamaker = 0.1;
  law.r0 = 0.4;
  return law;
}

double traction(const LennardJones& law, double r)
{
  double phi, dphi, d2phi;
  law.evaluate(r, phi, dphi, d2phi);
  return -dphi;
}

}  // namespace

TEST(LennardJones, EquilibriumStrongestAttractionAndWorkOfAdhesion)
{
  const auto law = base_law();
  EXPECT_NEAR(law.equilibrium_gap(), 0.2547, 5e-5);
  EXPECT_NEAR(law.strongest_attraction_gap(), 0.306, 5e-4);
  EXPECT_NEAR(traction(law, law.equilibrium_gap()), 0.0, 1e-13);
  // The strongest attraction is t_max of eq. 22 = 0.0618 E (E = 2 GPa = 2 nN/nm^2), at r_min.
  EXPECT_NEAR(-traction(law, law.strongest_attraction_gap()), law.max_traction(), 1e-12);
  EXPECT_NEAR(law.max_traction() / 2.0, 0.0618, 5e-5);
  for (double r : {0.29, 0.30, 0.31, 0.32}) EXPECT_GE(traction(law, r), -law.max_traction() - 1e-12);
  // w_adh = int_{r_eq}^inf -T dr (substitution r = r_eq / s, s in (0, 1], Gauss-Legendre on 8 x 64 points).
  double integral = 0.0;
  const int panels = 64;
  for (int p = 0; p < panels; ++p)
    for (int q = 0; q < 8; ++q) {
      double x, w;
      elements::gauss_point(8, q, x, w);
      const double s = (p + 0.5 * (x + 1.0)) / panels, ds = 0.5 * w / panels;
      const double r = law.equilibrium_gap() / s;
      integral += -traction(law, r) * law.equilibrium_gap() / (s * s) * ds;
    }
  EXPECT_NEAR(integral, law.work_of_adhesion(), 1e-9 * law.work_of_adhesion());
  EXPECT_NEAR(law.work_of_adhesion(), 0.03066, 5e-6);   // J/m^2 = nN/nm
  double phi, dphi, d2phi;
  law.evaluate(law.equilibrium_gap(), phi, dphi, d2phi);
  EXPECT_NEAR(phi, -law.work_of_adhesion(), 1e-14);
  // Pi_c0 = A_c w_adh for the paper's A_c = 49,524 nm^2: 759.3 E R0^3 (E R0^3 = 2 nN nm).
  EXPECT_NEAR(49524.0 * law.work_of_adhesion() / 2.0, 759.3, 0.05);
}

TEST(LennardJones, DerivativesAgainstFiniteDifferences)
{
  auto law = base_law();
  law.r_reg = 0.8 * law.equilibrium_gap();
  law.r_cut = 4.0;
  const double h = 1e-7;
  for (double r : {-0.1, 0.1, 0.2, 0.25, 0.2547, 0.3, 0.5, 1.0, 2.5, 3.0, 3.9}) {
    double p, d1, d2, pp, dp, d2p, pm, dm, d2m;
    law.evaluate(r, p, d1, d2);
    law.evaluate(r + h, pp, dp, d2p);
    law.evaluate(r - h, pm, dm, d2m);
    EXPECT_NEAR((pp - pm) / (2 * h), d1, 1e-6 * std::max(1.0, std::abs(d1))) << "r = " << r;
    EXPECT_NEAR((dp - dm) / (2 * h), d2, 1e-6 * std::max(1.0, std::abs(d2))) << "r = " << r;
  }
}

TEST(LennardJones, RegularizationIsC1AndFiniteAndTheCutOffConstant)
{
  auto law = base_law();
  law.r_reg = 0.8 * law.equilibrium_gap();
  law.r_cut = 4.0;
  double below[3], above[3];
  law.evaluate(law.r_reg - 1e-12, below[0], below[1], below[2]);
  law.evaluate(law.r_reg + 1e-12, above[0], above[1], above[2]);
  EXPECT_NEAR(below[0], above[0], 1e-9);
  EXPECT_NEAR(below[1], above[1], 1e-8 * std::abs(above[1]));
  EXPECT_NEAR(below[2], above[2], 1e-8 * std::abs(above[2]));   // constant slope continues the traction
  double phi, dphi, d2phi;
  for (double r : {0.0, -1.0}) {
    law.evaluate(r, phi, dphi, d2phi);
    EXPECT_TRUE(std::isfinite(phi) && std::isfinite(dphi));
    EXPECT_LT(dphi, 0.0);   // still repulsive: pushes the pad out
  }
  EXPECT_FALSE(law.evaluate(5.0, phi, dphi, d2phi));
  double at_cut, unused1, unused2;
  law.exact(4.0, at_cut, unused1, unused2);
  EXPECT_EQ(phi, at_cut);
  EXPECT_EQ(dphi, 0.0);
  // The taper from r_cut / 2 to r_cut: phi, phi', phi'' continuous at both ends, the law exact below r_cut / 2.
  for (double r : {2.0, 4.0}) {
    double a[3], b[3];
    law.evaluate(r - 1e-9, a[0], a[1], a[2]);
    law.evaluate(r + 1e-9, b[0], b[1], b[2]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-7 * (std::abs(a[k]) + 1e-6)) << "r = " << r << " k = " << k;
  }
  double exact[3], tapered[3];
  law.exact(1.99, exact[0], exact[1], exact[2]);
  law.evaluate(1.99, tapered[0], tapered[1], tapered[2]);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(exact[k], tapered[k]);
  // The cut-off leaves a tail of |phi(r_cut)| / w_adh = 0.54 (r0 / r_cut)^2 of the adhesion energy: 0.5 % here.
  EXPECT_NEAR(-at_cut / law.work_of_adhesion(), 0.5407 * std::pow(0.4 / 4.0, 2), 1e-4);
}

TEST(Stiction, ZeroTangentialTravelIsTheFrictionlessLaw)
{
  auto law = base_law();
  law.r_reg = 0.8 * law.equilibrium_gap();
  const contact::StictionLaw stiction{law, -law.equilibrium_gap()};
  for (double gap : {-0.05, 0.1, 0.2, 0.2547, 0.28, 0.306, 0.5, 2.0}) {
    const double X[3] = {12.0, -3.0, 0.0};
    const double x[3] = {12.0, -3.0, gap - law.equilibrium_gap()};   // straight above the anchor
    double phi, gradient[3], H[3][3];
    stiction.evaluate(X, x, phi, gradient, H);
    double p, d1, d2;
    law.evaluate(gap, p, d1, d2);
    EXPECT_NEAR(phi, p, 1e-14) << gap;
    EXPECT_NEAR(gradient[2], d1, 1e-12 * std::max(1.0, std::abs(d1))) << gap;
    EXPECT_NEAR(gradient[0], 0.0, 1e-15);
    EXPECT_NEAR(H[2][2], d2, 1e-10 * std::max(1.0, std::abs(d2))) << gap;
  }
}

TEST(Stiction, TangentialTravelIsResistedAndDerivativesMatch)
{
  const auto law = base_law();
  const contact::StictionLaw stiction{law, -law.equilibrium_gap()};
  const double X[3] = {5.0, 2.0, 0.0};
  const double x[3] = {5.12, 1.95, 0.04 - 0.0};   // slid by 0.13 nm, slightly lifted
  double phi, gradient[3], H[3][3];
  stiction.evaluate(X, x, phi, gradient, H);
  EXPECT_GT(gradient[0], 0.0);   // the energy grows with the slip: the force -grad phi pulls back to the anchor
  const double h = 1e-7;
  for (int j = 0; j < 3; ++j) {
    double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, pp, pm, gp[3], gm[3], Hp[3][3], Hm[3][3];
    xp[j] += h;
    xm[j] -= h;
    stiction.evaluate(X, xp, pp, gp, Hp);
    stiction.evaluate(X, xm, pm, gm, Hm);
    EXPECT_NEAR((pp - pm) / (2 * h), gradient[j], 1e-6 * std::abs(gradient[j]) + 1e-12);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR((gp[i] - gm[i]) / (2 * h), H[i][j], 1e-6 * std::abs(H[i][j]) + 1e-9);
  }
}

TEST(RoughSubstrate, ProjectionMatchesBruteForceSearch)
{
  contact::RoughSubstrate rough{-5.0, 8.0, 20.0, 100.0};
  for (const auto& x : {std::array<double, 3>{10.0, 5.0, 3.5}, std::array<double, 3>{37.0, -22.0, -2.0},
                        std::array<double, 3>{50.0, 86.6, 4.0}, std::array<double, 3>{-15.0, 40.0, -4.5}}) {
    contact::SurfacePoint p;
    ASSERT_TRUE(rough.project(x.data(), p));
    double best = 1e30, S, g[2], H[2][2];
    for (int i = -200; i <= 200; ++i)
      for (int j = -200; j <= 200; ++j) {
        const double xi = x[0] + 0.1 * i, eta = x[1] + 0.1 * j;
        rough.surface(xi, eta, S, g, H);
        best = std::min(best, std::hypot(x[0] - xi, x[1] - eta, x[2] - S));
      }
    // Refine the brute-force minimum around the grid optimum is not needed: the grid bounds it from above.
    EXPECT_LE(std::abs(p.distance), best + 1e-12);
    EXPECT_GT(std::abs(p.distance), best - 0.01);
    rough.surface(p.foot[0], p.foot[1], S, g, H);
    EXPECT_NEAR(p.foot[2], S, 1e-12);
    // x - foot is along the normal.
    const double d[3] = {x[0] - p.foot[0], x[1] - p.foot[1], x[2] - p.foot[2]};
    const double cross[3] = {d[1] * p.normal[2] - d[2] * p.normal[1], d[2] * p.normal[0] - d[0] * p.normal[2],
                             d[0] * p.normal[1] - d[1] * p.normal[0]};
    EXPECT_NEAR(std::hypot(cross[0], cross[1], cross[2]), 0.0, 1e-9);
  }
}

TEST(RoughSubstrate, NormalAndCurvatureAreDerivativesOfTheDistance)
{
  contact::RoughSubstrate rough{-5.0, 8.0, 20.0, 100.0};
  const double x[3] = {14.0, 7.0, 2.6};
  contact::SurfacePoint p;
  ASSERT_TRUE(rough.project(x, p));
  const double h = 1e-6;
  for (int j = 0; j < 3; ++j) {
    double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
    xp[j] += h;
    xm[j] -= h;
    contact::SurfacePoint pp, pm;
    rough.project(xp, pp);
    rough.project(xm, pm);
    EXPECT_NEAR((pp.distance - pm.distance) / (2 * h), p.normal[j], 1e-7);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR((pp.normal[i] - pm.normal[i]) / (2 * h), p.curvature[i][j], 1e-6);
  }
  // The curvature matrix is symmetric (a Hessian) and annihilates the normal.
  for (int i = 0; i < 3; ++i) {
    double Hn = 0.0;
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(p.curvature[i][j], p.curvature[j][i], 1e-12);
      Hn += p.curvature[i][j] * p.normal[j];
    }
    EXPECT_NEAR(Hn, 0.0, 1e-12);
  }
}
