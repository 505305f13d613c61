#pragma once
// Compressible Neo-Hookean solid (paper eqs. 7-9), a pure function of the deformation gradient F.
//
//   W(F)     = Lambda/2 (ln J)^2 + mu/2 (tr(F F^T) - 3) - mu ln J,          J = det F
//   P_iJ     = dW/dF_iJ = mu F_iJ + (Lambda ln J - mu) Finv_Ji               (first Piola-Kirchhoff)
//   A_iJkL   = dP_iJ/dF_kL = mu d_ik d_JL + Lambda Finv_Ji Finv_Lk - (Lambda ln J - mu) Finv_Jk Finv_Li
//   sigma    = P F^T / J = Lambda ln J / J I + mu / J (F F^T - I)              (Cauchy)
//
// with mu = E / (2 (1 + nu)), Lambda = 2 mu nu / (1 - 2 nu).
#include "laws/small_matrix.hpp"

#include <Kokkos_Core.hpp>

#include <cmath>

namespace spatula::laws {

struct NeoHookean {
  double mu = 0.0;
  double lambda = 0.0;

  KOKKOS_INLINE_FUNCTION static NeoHookean from_young(double young, double poisson)
  {
    NeoHookean law;
    law.mu = young / (2.0 * (1.0 + poisson));
    law.lambda = 2.0 * law.mu * poisson / (1.0 - 2.0 * poisson);
    return law;
  }

  // Energy density and first Piola-Kirchhoff stress; with `tangent` != nullptr also A = dP/dF as a 9 x 9 matrix,
  // tangent[3 i + J][3 k + L] = A_iJkL. Returns false (outputs unset) if J <= 0: the state is not admissible.
  KOKKOS_INLINE_FUNCTION bool evaluate(const double F[3][3], double& energy, double P[3][3],
                                       double (*tangent)[9] = nullptr) const
  {
    double Finv[3][3];
    const double J = invert(F, Finv);
    if (!(J > 0.0)) return false;
    const double log_J = ::log(J);   // the C math function: callable on every Kokkos backend
    double trace_C = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) trace_C += F[i][j] * F[i][j];
    energy = 0.5 * lambda * log_J * log_J + 0.5 * mu * (trace_C - 3.0) - mu * log_J;
    const double factor = lambda * log_J - mu;
    for (int i = 0; i < 3; ++i)
      for (int J_ = 0; J_ < 3; ++J_) P[i][J_] = mu * F[i][J_] + factor * Finv[J_][i];
    if (tangent)
      for (int i = 0; i < 3; ++i)
        for (int J_ = 0; J_ < 3; ++J_)
          for (int k = 0; k < 3; ++k)
            for (int L = 0; L < 3; ++L)
              tangent[3 * i + J_][3 * k + L] = (i == k && J_ == L ? mu : 0.0) + lambda * Finv[J_][i] * Finv[L][k] -
                                          factor * Finv[J_][k] * Finv[L][i];
    return true;
  }

  // Cauchy stress sigma = P F^T / J.
  KOKKOS_INLINE_FUNCTION bool cauchy(const double F[3][3], double sigma[3][3]) const
  {
    double energy, P[3][3];
    if (!evaluate(F, energy, P)) return false;
    const double J = determinant(F);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double sum = 0.0;
        for (int K = 0; K < 3; ++K) sum += P[i][K] * F[j][K];
        sigma[i][j] = sum / J;
      }
    return true;
  }
};

}  // namespace spatula::laws
