// Contact faces (Q1C1 and Q1C2) with every law and substrate: residual and tangent against finite differences of
// the energy and residual; the undeformed face at the equilibrium gap stores -w_adh per unit area.
#include "contact/contact_face.hpp"

#include "skewed_face.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatula;

namespace {

contact::LennardJones law()
{
  contact::LennardJones lj;
  lj.r_reg = 0.8 * lj.equilibrium_gap();
  lj.r_cut = 5.0;
  return lj;
}

// A 6 nm x 5 nm face on Z = 0 (slightly skewed) and a displacement lifting it 0..0.6 nm unevenly with some sliding.
template <class Surface>
void face_state(double X[Surface::nodes][3], double u[Surface::nodes][3])
{
  test::skewed_face<Surface>(X);
  for (int k = 0; k < Surface::nodes; ++k) {
    const double s = test::face_node_parameters[k][0], t = test::face_node_parameters[k][1];
    u[k][0] = 0.05 * std::sin(1.0 + k);
    u[k][1] = 0.04 * std::cos(2.0 * k);
    u[k][2] = 0.12 * (s + 1.0) + 0.06 * (t + 1.0) + 0.03 * std::sin(3.0 * k);
  }
}

// Residual and tangent against central differences; the anchors are the reference positions moved by `shift`.
template <class Surface, class Integrand>
void expect_consistent(const Integrand& integrand, double lift = 0.0, const double shift[3] = nullptr)
{
  constexpr int n = Surface::nodes, dofs = 3 * n;
  double X[n][3], A[n][3], u[n][3], r[dofs], K[dofs][dofs];
  face_state<Surface>(X, u);
  for (int k = 0; k < n; ++k) {
    u[k][2] += lift;
    for (int i = 0; i < 3; ++i) A[k][i] = X[k][i] + (shift ? shift[i] : 0.0);
  }
  const auto result = contact::contact_face<Surface>(integrand, X, A, u, 5, r, K);
  ASSERT_GT(result.active_points, 0);
  const double h = 1e-7;
  double worst_r = 0.0, worst_K = 0.0, largest_r = 0.0, largest_K = 0.0;
  for (int q = 0; q < dofs; ++q) {
    double up[n][3], um[n][3], rp[dofs], rm[dofs];
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < 3; ++i) up[k][i] = um[k][i] = u[k][i];
    up[q / 3][q % 3] += h;
    um[q / 3][q % 3] -= h;
    const auto plus = contact::contact_face<Surface>(integrand, X, A, up, 5, rp);
    const auto minus = contact::contact_face<Surface>(integrand, X, A, um, 5, rm);
    worst_r = std::max(worst_r, std::abs((plus.energy - minus.energy) / (2 * h) - r[q]));
    largest_r = std::max(largest_r, std::abs(r[q]));
    for (int p = 0; p < dofs; ++p) {
      worst_K = std::max(worst_K, std::abs((rp[p] - rm[p]) / (2 * h) - K[p][q]));
      largest_K = std::max(largest_K, std::abs(K[p][q]));
    }
  }
  EXPECT_LT(worst_r / largest_r, 1e-6);
  EXPECT_LT(worst_K / largest_K, 1e-6);
  for (int p = 0; p < dofs; ++p)
    for (int q = 0; q < dofs; ++q) EXPECT_NEAR(K[p][q], K[q][p], 1e-10 * largest_K);
}

}  // namespace

TEST(ContactFace, FrictionlessFlatTangents)
{
  const auto lj = law();
  contact::FrictionlessIntegrand<contact::FlatSubstrate> integrand{lj, {-lj.equilibrium_gap()}};
  expect_consistent<elements::Quad4Surface>(integrand);
  expect_consistent<elements::Quad9Surface>(integrand);
}

TEST(ContactFace, FrictionlessRoughTangentsIncludeCurvature)
{
  const auto lj = law();
  contact::RoughSubstrate rough{-lj.equilibrium_gap() - 3.0, 3.0, 4.0, 10.0};   // sharp bumps under a 6 nm face
  contact::FrictionlessIntegrand<contact::RoughSubstrate> integrand{lj, rough};
  expect_consistent<elements::Quad4Surface>(integrand, 0.3);
  expect_consistent<elements::Quad9Surface>(integrand, 0.3);
}

TEST(ContactFace, StictionTangents)
{
  const auto lj = law();
  contact::StictionIntegrand integrand{{lj, -lj.equilibrium_gap()}};
  expect_consistent<elements::Quad4Surface>(integrand);
  expect_consistent<elements::Quad9Surface>(integrand);
}

TEST(ContactFace, StictionTangentsWithMovedAnchors)
{
  const auto lj = law();
  contact::StictionIntegrand integrand{{lj, -lj.equilibrium_gap()}};
  const double shift[3] = {0.3, -0.2, 0.7};   // anchored at a deformed state: travel of a few tenths of a nm
  expect_consistent<elements::Quad4Surface>(integrand, 0.0, shift);
  expect_consistent<elements::Quad9Surface>(integrand, 0.0, shift);
}

// Anchored where the face is now, stiction has no tangential travel: energy and forces are the frictionless ones
// (what makes switching the law on at a restart state seamless); anchored at the reference positions it differs.
TEST(ContactFace, StictionAnchoredAtTheCurrentStateIsFrictionless)
{
  const auto lj = law();
  contact::StictionIntegrand stiction{{lj, -lj.equilibrium_gap()}};
  contact::FrictionlessIntegrand<contact::FlatSubstrate> frictionless{lj, {-lj.equilibrium_gap()}};
  double X[9][3], A[9][3], u[9][3], r_stiction[27], r_frictionless[27], r_reference[27];
  face_state<elements::Quad9Surface>(X, u);
  for (int k = 0; k < 9; ++k)
    for (int i = 0; i < 3; ++i) A[k][i] = X[k][i] + u[k][i];
  const auto anchored = contact::contact_face<elements::Quad9Surface>(stiction, X, A, u, 5, r_stiction);
  const auto plain = contact::contact_face<elements::Quad9Surface>(frictionless, X, u, 5, r_frictionless);
  contact::contact_face<elements::Quad9Surface>(stiction, X, u, 5, r_reference);   // anchors at X
  ASSERT_GT(plain.active_points, 0);
  EXPECT_NEAR(anchored.energy, plain.energy, 1e-12 * std::abs(plain.energy));
  double largest = 0.0, difference = 0.0;
  for (int p = 0; p < 27; ++p) {
    EXPECT_NEAR(r_stiction[p], r_frictionless[p], 1e-12 * (1.0 + std::abs(r_frictionless[p])));
    largest = std::max(largest, std::abs(r_frictionless[p]));
    difference = std::max(difference, std::abs(r_reference[p] - r_frictionless[p]));
  }
  EXPECT_GT(difference, 1e-3 * largest);   // the face has slid: from the reference positions there is travel
}

TEST(ContactFace, UndeformedFaceAtTheEquilibriumGapStoresMinusWorkOfAdhesion)
{
  const auto lj = law();
  contact::FrictionlessIntegrand<contact::FlatSubstrate> integrand{lj, {-lj.equilibrium_gap()}};
  double X[9][3], u[9][3] = {}, r[27];
  face_state<elements::Quad9Surface>(X, u);
  for (auto& node : u) node[0] = node[1] = node[2] = 0.0;
  const auto result = contact::contact_face<elements::Quad9Surface>(integrand, X, u, 3, r);
  EXPECT_NEAR(result.energy, -lj.work_of_adhesion() * result.area, 1e-14);
  for (double value : r) EXPECT_NEAR(value, 0.0, 1e-14);   // traction-free start
  // The face area (bilinear quadrilateral): shoelace of the corners.
  EXPECT_NEAR(result.area, 0.5 * std::abs((6.0 * 5.0 - 6.5 * 0.5) + (6.5 * 5.2 - 0.2 * 5.0) + (0.2 * 0.0 - 0.0 * 5.2)), 1e-12);
}

TEST(ContactFace, SurfaceShapesInterpolateExactly)
{
  // Q9 reproduces biquadratic fields, Q4 bilinear ones; both sum to one.
  for (double s : {-0.7, 0.1, 0.9})
    for (double t : {-0.3, 0.6}) {
      double N[9], dN[9][2];
      elements::Quad9Surface::evaluate(s, t, N, dN);
      const double nodes[9][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, 0}};
      double sum = 0.0, field = 0.0, ds = 0.0;
      for (int k = 0; k < 9; ++k) {
        const double a = nodes[k][0], b = nodes[k][1];
        sum += N[k];
        field += N[k] * (a * a * b * b + 2 * a * b - b * b);
        ds += dN[k][0] * (a * a * b * b + 2 * a * b - b * b);
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      EXPECT_NEAR(field, s * s * t * t + 2 * s * t - t * t, 1e-14);
      EXPECT_NEAR(ds, 2 * s * t * t + 2 * t, 1e-13);
    }
}
