#pragma once
// Total-Lagrangian solid elements for a hyperelastic law (paper eqs. 4-5): element energy, residual and tangent
// on fixed-size stack arrays, for use inside Kokkos kernels. Two shapes: the trilinear hexahedron (Hex8) and the
// Q1C2 contact-enriched hexahedron (Hex13: its bottom face biquadratic with 4 mid-edge nodes and a centre node,
// linear through the thickness, the top face bilinear), which keeps the field conforming with plain Hex8
// neighbours above it and with enriched neighbours beside it.
//
//   F = I + sum_a u_a (x) G_a,  G_a = dN_a/dX
//   energy = sum_q W(F_q) w_q detJ_q
//   r_ai   = sum_q P_iJ(F_q) G_aJ w_q detJ_q
//   K_aibk = sum_q G_aJ A_iJkL(F_q) G_bL w_q detJ_q
// with an order x order x order Gauss rule. The law provides evaluate(F, W, P, A) (see laws/neo_hookean.hpp).
#include "elements/gauss_rule.hpp"
#include "mesh/hexahedron.hpp"
#include "elements/quadrilateral_shape.hpp"
#include "laws/small_matrix.hpp"

namespace spatula::elements {

enum class ElementStatus : int { ok = 0, invalid_reference = 1, inverted = 2 };

struct Hex8Shape {
  static constexpr int nodes = 8;
  KOKKOS_INLINE_FUNCTION static void evaluate(const double xi[3], double N[8], double dN[8][3])
  {
    mesh::hex_shape(xi, N, dN);
  }
};

// Nodes 0-3 bottom corners, 4-7 top corners (as Hex8), 8-11 bottom mid-edges (01, 12, 23, 30), 12 bottom centre.
struct Hex13Shape {
  static constexpr int nodes = 13;
  // The bottom face's nodes in Quad9Surface order.
  KOKKOS_INLINE_FUNCTION static int bottom_node(int k) { return k < 4 ? k : k + 4; }
  KOKKOS_INLINE_FUNCTION static void evaluate(const double xi[3], double N[13], double dN[13][3])
  {
    double bottom[9], dbottom[9][2], top[4], dtop[4][2];
    Quad9Surface::evaluate(xi[0], xi[1], bottom, dbottom);
    Quad4Surface::evaluate(xi[0], xi[1], top, dtop);
    const double below = 0.5 * (1.0 - xi[2]), above = 0.5 * (1.0 + xi[2]);
    for (int k = 0; k < 9; ++k) {
      const int a = bottom_node(k);
      N[a] = bottom[k] * below;
      dN[a][0] = dbottom[k][0] * below;
      dN[a][1] = dbottom[k][1] * below;
      dN[a][2] = -0.5 * bottom[k];
    }
    for (int k = 0; k < 4; ++k) {
      N[4 + k] = top[k] * above;
      dN[4 + k][0] = dtop[k][0] * above;
      dN[4 + k][1] = dtop[k][1] * above;
      dN[4 + k][2] = 0.5 * top[k];
    }
  }
};

// Gradients G[a][J] = dN_a/dX_J at xi; returns the reference Jacobian determinant (callers reject det <= 0).
template <class Shape>
KOKKOS_INLINE_FUNCTION double reference_gradients(const double X[Shape::nodes][3], const double xi[3],
                                                  double G[Shape::nodes][3])
{
  constexpr int n = Shape::nodes;
  double shape[n], gradient[n][3], jacobian[3][3], inverse[3][3];
  Shape::evaluate(xi, shape, gradient);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (int a = 0; a < n; ++a) sum += X[a][i] * gradient[a][j];
      jacobian[i][j] = sum;
    }
  const double det = laws::invert(jacobian, inverse);   // a singular map leaves G = 0
  for (int a = 0; a < n; ++a)
    for (int J = 0; J < 3; ++J)
      G[a][J] = gradient[a][0] * inverse[0][J] + gradient[a][1] * inverse[1][J] + gradient[a][2] * inverse[2][J];
  return det;
}

template <int n>
KOKKOS_INLINE_FUNCTION void deformation_gradient(const double u[n][3], const double G[n][3], double F[3][3])
{
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J) {
      double sum = i == J ? 1.0 : 0.0;
      for (int a = 0; a < n; ++a) sum += u[a][i] * G[a][J];
      F[i][J] = sum;
    }
}

// Energy, residual r[3n] (index 3 a + i) and, if K != nullptr, tangent K[3n][3n] of one element.
template <class Shape, class Law>
KOKKOS_INLINE_FUNCTION ElementStatus solid_element(const Law& law, const double X[Shape::nodes][3],
                                                   const double u[Shape::nodes][3], int order, double& energy,
                                                   double r[3 * Shape::nodes], double (*K)[3 * Shape::nodes] = nullptr)
{
  constexpr int n = Shape::nodes, dofs = 3 * n;
  energy = 0.0;
  for (int p = 0; p < dofs; ++p) r[p] = 0.0;
  if (K)
    for (int p = 0; p < dofs; ++p)
      for (int q = 0; q < dofs; ++q) K[p][q] = 0.0;
  for (int i0 = 0; i0 < order; ++i0)
    for (int i1 = 0; i1 < order; ++i1)
      for (int i2 = 0; i2 < order; ++i2) {
        double xi[3], rule_weight;
        gauss_point_3d(order, i0, i1, i2, xi, rule_weight);
        double G[n][3];
        const double det = reference_gradients<Shape>(X, xi, G);
        if (!(det > 0.0)) return ElementStatus::invalid_reference;
        const double weight = rule_weight * det;
        double F[3][3], W, P[3][3], A[9][9];
        deformation_gradient<n>(u, G, F);
        if (!law.evaluate(F, W, P, K ? A : nullptr)) return ElementStatus::inverted;
        energy += W * weight;
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i)
            r[3 * a + i] += (P[i][0] * G[a][0] + P[i][1] * G[a][1] + P[i][2] * G[a][2]) * weight;
        if (!K) continue;
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i) {
            // AG[k][L] = sum_J G_aJ A_iJkL
            double AG[9];
            for (int c = 0; c < 9; ++c)
              AG[c] = G[a][0] * A[3 * i][c] + G[a][1] * A[3 * i + 1][c] + G[a][2] * A[3 * i + 2][c];
            for (int b = a; b < n; ++b)   // the node blocks on and above the diagonal; the rest mirrored below
              for (int k = 0; k < 3; ++k)
                K[3 * a + i][3 * b + k] +=
                    (AG[3 * k] * G[b][0] + AG[3 * k + 1] * G[b][1] + AG[3 * k + 2] * G[b][2]) * weight;
          }
      }
  // A hyperelastic law's A_iJkL = d2W/dF_iJ dF_kL is symmetric (A_iJkL = A_kLiJ), and so is K.
  if (K)
    for (int a = 1; a < n; ++a)
      for (int b = 0; b < a; ++b)
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k) K[3 * a + i][3 * b + k] = K[3 * b + k][3 * a + i];
  return ElementStatus::ok;
}

template <class Law>
KOKKOS_INLINE_FUNCTION ElementStatus hex8_solid(const Law& law, const double X[8][3], const double u[8][3], int order,
                                                double& energy, double r[24], double (*K)[24] = nullptr)
{
  return solid_element<Hex8Shape>(law, X, u, order, energy, r, K);
}

// Mean of tr(sigma) over the element's Gauss points (the paper's field I1 = tr sigma, before dividing by E).
template <class Shape, class Law>
KOKKOS_INLINE_FUNCTION double mean_cauchy_trace(const Law& law, const double X[Shape::nodes][3],
                                                const double u[Shape::nodes][3], int order)
{
  constexpr int n = Shape::nodes;
  double sum = 0.0, volume = 0.0;
  for (int i0 = 0; i0 < order; ++i0)
    for (int i1 = 0; i1 < order; ++i1)
      for (int i2 = 0; i2 < order; ++i2) {
        double xi[3], rule_weight;
        gauss_point_3d(order, i0, i1, i2, xi, rule_weight);
        double G[n][3], F[3][3], sigma[3][3];
        const double weight = rule_weight * reference_gradients<Shape>(X, xi, G);
        deformation_gradient<n>(u, G, F);
        if (!law.cauchy(F, sigma)) continue;
        sum += (sigma[0][0] + sigma[1][1] + sigma[2][2]) * weight;
        volume += weight;
      }
  return volume > 0.0 ? sum / volume : 0.0;
}

}  // namespace spatula::elements
