#pragma once
// Total-Lagrangian trilinear hexahedron for a hyperelastic law (paper eqs. 4-5): element energy, residual and
// tangent on fixed-size stack arrays, for use inside Kokkos kernels.
//
//   F = I + sum_a u_a (x) G_a,  G_a = dN_a/dX
//   energy = sum_q W(F_q) w_q detJ_q
//   r_ai   = sum_q P_iJ(F_q) G_aJ w_q detJ_q
//   K_aibk = sum_q G_aJ A_iJkL(F_q) G_bL w_q detJ_q
// with an order x order x order Gauss rule. The law provides evaluate(F, W, P, A) (see laws/neo_hookean.hpp).
#include "gauss_rule.hpp"
#include "hexahedron.hpp"
#include "small_matrix.hpp"

namespace spatula::elements {

enum class ElementStatus : int { ok = 0, invalid_reference = 1, inverted = 2 };

// Gradients G[a][J] = dN_a/dX_J at xi; returns the reference Jacobian determinant (callers reject det <= 0).
KOKKOS_INLINE_FUNCTION double hex8_reference_gradients(const double X[8][3], const double xi[3], double G[8][3])
{
  double shape[8], gradient[8][3], jacobian[3][3], inverse[3][3];
  mesh::hex_shape(xi, shape, gradient);
  mesh::hex_jacobian(X, xi, jacobian);
  const double det = laws::invert(jacobian, inverse);   // a singular map leaves G = 0
  for (int a = 0; a < 8; ++a)
    for (int J = 0; J < 3; ++J)
      G[a][J] = gradient[a][0] * inverse[0][J] + gradient[a][1] * inverse[1][J] + gradient[a][2] * inverse[2][J];
  return det;
}

KOKKOS_INLINE_FUNCTION void hex8_deformation_gradient(const double u[8][3], const double G[8][3], double F[3][3])
{
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J) {
      double sum = i == J ? 1.0 : 0.0;
      for (int a = 0; a < 8; ++a) sum += u[a][i] * G[a][J];
      F[i][J] = sum;
    }
}

// Energy, residual r[24] (index 3 a + i) and, if K != nullptr, tangent K[24][24] of one element.
template <class Law>
KOKKOS_INLINE_FUNCTION ElementStatus hex8_solid(const Law& law, const double X[8][3], const double u[8][3],
                                                int order, double& energy, double r[24], double (*K)[24] = nullptr)
{
  energy = 0.0;
  for (int p = 0; p < 24; ++p) r[p] = 0.0;
  if (K)
    for (int p = 0; p < 24; ++p)
      for (int q = 0; q < 24; ++q) K[p][q] = 0.0;
  for (int i0 = 0; i0 < order; ++i0)
    for (int i1 = 0; i1 < order; ++i1)
      for (int i2 = 0; i2 < order; ++i2) {
        double xi[3], w0, w1, w2;
        gauss_point(order, i0, xi[0], w0);
        gauss_point(order, i1, xi[1], w1);
        gauss_point(order, i2, xi[2], w2);
        double G[8][3];
        const double det = hex8_reference_gradients(X, xi, G);
        if (!(det > 0.0)) return ElementStatus::invalid_reference;
        const double weight = w0 * w1 * w2 * det;
        double F[3][3], W, P[3][3], A[9][9];
        hex8_deformation_gradient(u, G, F);
        if (!law.evaluate(F, W, P, K ? A : nullptr)) return ElementStatus::inverted;
        energy += W * weight;
        for (int a = 0; a < 8; ++a)
          for (int i = 0; i < 3; ++i)
            r[3 * a + i] += (P[i][0] * G[a][0] + P[i][1] * G[a][1] + P[i][2] * G[a][2]) * weight;
        if (!K) continue;
        for (int a = 0; a < 8; ++a)
          for (int i = 0; i < 3; ++i) {
            // AG[k][L] = sum_J G_aJ A_iJkL
            double AG[9];
            for (int c = 0; c < 9; ++c)
              AG[c] = G[a][0] * A[3 * i][c] + G[a][1] * A[3 * i + 1][c] + G[a][2] * A[3 * i + 2][c];
            for (int b = 0; b < 8; ++b)
              for (int k = 0; k < 3; ++k)
                K[3 * a + i][3 * b + k] +=
                    (AG[3 * k] * G[b][0] + AG[3 * k + 1] * G[b][1] + AG[3 * k + 2] * G[b][2]) * weight;
          }
      }
  return ElementStatus::ok;
}

// Mean of tr(sigma) over the element's Gauss points (the paper's field I1 = tr sigma, before dividing by E).
template <class Law>
KOKKOS_INLINE_FUNCTION double hex8_mean_cauchy_trace(const Law& law, const double X[8][3], const double u[8][3],
                                                     int order)
{
  double sum = 0.0, volume = 0.0;
  for (int i0 = 0; i0 < order; ++i0)
    for (int i1 = 0; i1 < order; ++i1)
      for (int i2 = 0; i2 < order; ++i2) {
        double xi[3], w0, w1, w2;
        gauss_point(order, i0, xi[0], w0);
        gauss_point(order, i1, xi[1], w1);
        gauss_point(order, i2, xi[2], w2);
        double G[8][3], F[3][3], sigma[3][3];
        const double weight = w0 * w1 * w2 * hex8_reference_gradients(X, xi, G);
        hex8_deformation_gradient(u, G, F);
        if (!law.cauchy(F, sigma)) continue;
        sum += (sigma[0][0] + sigma[1][1] + sigma[2][2]) * weight;
        volume += weight;
      }
  return volume > 0.0 ? sum / volume : 0.0;
}

}  // namespace spatula::elements
