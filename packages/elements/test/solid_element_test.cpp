// The Hex8 and Hex13 solid kernels: residual and tangent against finite differences on a distorted element, the
// patch test, rigid motions, and bad states.
#include "laws/neo_hookean.hpp"
#include "elements/solid_element.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace spatula;
using elements::ElementStatus;

namespace {

const laws::NeoHookean law = laws::NeoHookean::from_young(2.0, 0.2);

// A distorted hexahedron (non-parallel faces, warped top).
const double X0[8][3] = {{0.0, 0.0, 0.0}, {2.1, 0.2, -0.1}, {2.3, 1.9, 0.2}, {-0.2, 1.7, 0.1},
                         {0.1, -0.1, 1.2}, {1.9, 0.1, 1.0},  {2.2, 2.1, 1.5}, {0.2, 1.8, 1.1}};

void some_displacement(double u[8][3])
{
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) u[a][i] = 0.08 * std::sin(1.3 * a + 2.1 * i + 0.4) + 0.03 * X0[a][(i + 1) % 3];
}

double energy_at(const double u[8][3], int order = 2)
{
  double energy, r[24];
  EXPECT_EQ(elements::hex8_solid(law, X0, u, order, energy, r), ElementStatus::ok);
  return energy;
}

// The largest difference between K[p][q] and the central difference of r_p in u_q (step 1e-6), over the largest
// |K[p][q]|, for an element of `Shape` at (X, u); K is the element's tangent there.
template <class Shape, int n = Shape::nodes>
double tangent_error(const double (&X)[n][3], const double (&u)[n][3], int order, const double (&K)[3 * n][3 * n])
{
  const double h = 1e-6;
  double worst = 0.0, largest = 0.0;
  for (int q = 0; q < 3 * n; ++q) {
    double up[n][3], um[n][3], rp[3 * n], rm[3 * n], e;
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) up[a][i] = um[a][i] = u[a][i];
    up[q / 3][q % 3] += h;
    um[q / 3][q % 3] -= h;
    elements::solid_element<Shape>(law, X, up, order, e, rp);
    elements::solid_element<Shape>(law, X, um, order, e, rm);
    for (int p = 0; p < 3 * n; ++p) {
      worst = std::max(worst, std::abs((rp[p] - rm[p]) / (2 * h) - K[p][q]));
      largest = std::max(largest, std::abs(K[p][q]));
    }
  }
  return worst / largest;
}

}  // namespace

TEST(SolidHex8, ResidualIsTheEnergyGradient)
{
  double u[8][3], energy, r[24];
  some_displacement(u);
  ASSERT_EQ(elements::hex8_solid(law, X0, u, 2, energy, r), ElementStatus::ok);
  const double h = 1e-6;
  double worst = 0.0, largest = 0.0;
  for (int p = 0; p < 24; ++p) {
    double up[8][3], um[8][3];
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i) up[a][i] = um[a][i] = u[a][i];
    up[p / 3][p % 3] += h;
    um[p / 3][p % 3] -= h;
    const double derivative = (energy_at(up) - energy_at(um)) / (2 * h);
    worst = std::max(worst, std::abs(derivative - r[p]));
    largest = std::max(largest, std::abs(r[p]));
  }
  EXPECT_LT(worst / largest, 1e-6);
}

TEST(SolidHex8, TangentIsTheResidualDerivativeForEveryQuadratureOrder)
{
  for (int order : {1, 2, 3}) {
    double u[8][3], energy, r[24], K[24][24];
    some_displacement(u);
    ASSERT_EQ(elements::hex8_solid(law, X0, u, order, energy, r, K), ElementStatus::ok);
    EXPECT_LT(tangent_error<elements::Hex8Shape>(X0, u, order, K), 1e-6) << "order " << order;
    double largest = 0.0;
    for (int p = 0; p < 24; ++p)
      for (int q = 0; q < 24; ++q) largest = std::max(largest, std::abs(K[p][q]));
    for (int p = 0; p < 24; ++p)
      for (int q = 0; q < 24; ++q) EXPECT_NEAR(K[p][q], K[q][p], 1e-10 * largest);
  }
}

TEST(SolidHex8, RigidMotionStoresNothing)
{
  const double c = std::cos(0.7), s = std::sin(0.7);   // rotation about an axis + translation
  double u[8][3];
  for (int a = 0; a < 8; ++a) {
    const double x = X0[a][0], y = X0[a][1], z = X0[a][2];
    u[a][0] = c * x - s * z + 0.3 - x;
    u[a][1] = y - 1.0 - y;
    u[a][2] = s * x + c * z + 2.0 - z;
  }
  double energy, r[24];
  ASSERT_EQ(elements::hex8_solid(law, X0, u, 2, energy, r), ElementStatus::ok);
  EXPECT_NEAR(energy, 0.0, 1e-13);
  for (double value : r) EXPECT_NEAR(value, 0.0, 1e-13);
}

// Patch test: a 2 x 2 x 2 block of distorted elements (the shared centre node and the face centres moved) under a
// homogeneous deformation u = (F - I) X. Trilinear elements reproduce it exactly: the interior node feels no force
// and the energy is W(F) times the volume.
TEST(SolidHex8, PatchTestHomogeneousDeformationIsExact)
{
  std::vector<std::array<double, 3>> nodes;
  auto id = [](int i, int j, int k) { return i + 3 * j + 9 * k; };
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        std::array<double, 3> x = {double(i), double(j), double(k)};
        const int interior = (i == 1) + (j == 1) + (k == 1);
        if (interior >= 2)   // face and body centres move: the elements are distorted
          for (int d = 0; d < 3; ++d) x[d] += 0.17 * std::sin(3.0 * i + 5.0 * j + 7.0 * k + d);
        nodes.push_back(x);
      }
  const double F[3][3] = {{1.2, 0.1, 0.05}, {-0.1, 0.9, 0.2}, {0.03, 0.07, 1.1}};
  const int centre = id(1, 1, 1);
  double centre_force[3] = {0, 0, 0}, total_energy = 0.0, volume = 0.0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const int element[8] = {id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
                                id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        double X[8][3] = {}, u[8][3] = {}, zero[8][3] = {};
        for (int a = 0; a < 8; ++a)
          for (int d = 0; d < 3; ++d) X[a][d] = nodes[element[a]][d];
        for (int a = 0; a < 8; ++a)
          for (int d = 0; d < 3; ++d) u[a][d] = F[d][0] * X[a][0] + F[d][1] * X[a][1] + F[d][2] * X[a][2] - X[a][d];
        double energy, r[24], reference_energy;
        ASSERT_EQ(elements::hex8_solid(law, X, u, 2, energy, r), ElementStatus::ok);
        total_energy += energy;
        // Volume from the reference configuration: energy of nothing is zero, so integrate 1 with the rule.
        for (int q = 0; q < 8; ++q) {
          const double xi[3] = {mesh::hex_node_coordinate(q, 0) / std::sqrt(3.0),
                                mesh::hex_node_coordinate(q, 1) / std::sqrt(3.0),
                                mesh::hex_node_coordinate(q, 2) / std::sqrt(3.0)};
          double jacobian[3][3];
          volume += mesh::hex_jacobian(X, xi, jacobian);
        }
        elements::hex8_solid(law, X, zero, 2, reference_energy, r);
        EXPECT_EQ(reference_energy, 0.0);
        elements::hex8_solid(law, X, u, 2, energy, r);
        for (int a = 0; a < 8; ++a)
          if (element[a] == centre)
            for (int d = 0; d < 3; ++d) centre_force[d] += r[3 * a + d];
      }
  double W, P[3][3];
  law.evaluate(F, W, P);
  EXPECT_NEAR(total_energy, W * volume, 1e-12 * W * volume);
  for (double f : centre_force) EXPECT_NEAR(f, 0.0, 1e-12);
}

TEST(SolidHex8, InvertedElementAndInvalidReferenceAreReported)
{
  double u[8][3] = {}, energy, r[24];
  for (int a = 4; a < 8; ++a) u[a][2] = -2.5;   // the top pushed through the bottom
  EXPECT_EQ(elements::hex8_solid(law, X0, u, 2, energy, r), ElementStatus::inverted);
  double flipped[8][3];
  for (int a = 0; a < 8; ++a)
    for (int d = 0; d < 3; ++d) flipped[a][d] = X0[(a + 4) % 8][d];   // top and bottom swapped: det J < 0
  double zero[8][3] = {};
  EXPECT_EQ(elements::hex8_solid(law, flipped, zero, 2, energy, r), ElementStatus::invalid_reference);
}

TEST(SolidHex8, CauchyTraceOfUniaxialStretch)
{
  const double e = 1e-6;
  double u[8][3];
  for (int a = 0; a < 8; ++a) {
    u[a][0] = e * X0[a][0];
    u[a][1] = u[a][2] = 0.0;
  }
  // tr sigma = (3 lambda + 2 mu) e for small e
  EXPECT_NEAR(elements::mean_cauchy_trace<elements::Hex8Shape>(law, X0, u, 2) / e, 3 * law.lambda + 2 * law.mu, 1e-4);
}

// The Q1C2 enriched hexahedron: its bottom face biquadratic (mid-edge nodes 8-11 on edges 01, 12, 23, 30, centre
// node 12), here slightly curved; the tangent (filled above its node-block diagonal and mirrored) against central
// differences of the residual.
TEST(SolidHex13, TangentIsTheResidualDerivative)
{
  double X[13][3], u[13][3];
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) X[a][i] = X0[a][i];
  for (int e = 0; e < 4; ++e)
    for (int i = 0; i < 3; ++i) X[8 + e][i] = 0.5 * (X0[e][i] + X0[(e + 1) % 4][i]) + (i == 2 ? 0.05 * (e - 1.5) : 0.0);
  for (int i = 0; i < 3; ++i) X[12][i] = 0.25 * (X0[0][i] + X0[1][i] + X0[2][i] + X0[3][i]) - (i == 2 ? 0.04 : 0.0);
  for (int a = 0; a < 13; ++a)
    for (int i = 0; i < 3; ++i) u[a][i] = 0.08 * std::sin(1.3 * a + 2.1 * i + 0.4) + 0.03 * X[a][(i + 1) % 3];
  using elements::Hex13Shape;
  for (int order : {2, 3}) {
    double energy, r[39], K[39][39];
    ASSERT_EQ(elements::solid_element<Hex13Shape>(law, X, u, order, energy, r, K), ElementStatus::ok);
    EXPECT_LT(tangent_error<Hex13Shape>(X, u, order, K), 1e-6) << "order " << order;
  }
}
