#pragma once
// Contact elements on the pad's bottom surface (paper eqs. 10-18): the adhesion energy and its first and second
// variations integrated over the undeformed face with an order x order Gauss rule,
//
//   energy = sum_q phi(x_q) dA_q,  r_kI = sum_q N_k dphi/dx_I dA_q,  K_kI,lJ = sum_q N_k N_l d2phi/dx_I dx_J dA_q,
//
// x_q = sum_k N_k (X_k + u_k). The face is interpolated bilinearly (Q1C1: 4 nodes) or biquadratically (Q1C2: the
// 4 corners, 4 mid-edge nodes and the centre, in that order). The adhesion integrand (law x substrate) is a
// template parameter: evaluate(A, x, phi, dphi/dx, d2phi/dx2 or nullptr) -> within the cut-off?, with A = sum_k N_k A_k
// the point's anchor: where the stiction law measures tangential travel from (the frictionless law ignores it). The
// anchors A_k are the reference positions X_k unless a run re-anchors them at a deformed state.
// A law with state (friction_integrand.hpp) declares `history_size` values per quadrature point and evaluates with
// evaluate(A, x, history in, trial history out, phi, dphi/dx, d2phi/dx2 or nullptr); the face then takes the points'
// histories in (order x order x history_size values, point (a, b) at (a order + b) history_size) and writes their
// trial histories, which the caller commits only at a converged state.
#include "contact/lennard_jones.hpp"
#include "contact/stiction.hpp"
#include "contact/substrate.hpp"
#include "elements/gauss_rule.hpp"
#include "elements/quadrilateral_shape.hpp"

#include <type_traits>
#include <utility>

namespace spatula::contact {

// The frictionless law over any substrate: phi(d(x)), grad = phi' n, Hessian = phi'' n n + phi' grad n (the last
// term only where the substrate is curved).
template <class Substrate>
struct FrictionlessIntegrand {
  contact::LennardJones law;
  Substrate substrate;
  static constexpr bool curved = !std::is_same<Substrate, contact::FlatSubstrate>::value;

  KOKKOS_INLINE_FUNCTION double far_bound(const double x[3]) const { return substrate.distance_bound(x); }
  KOKKOS_INLINE_FUNCTION double cut_off() const { return law.r_cut; }
  // The gap at x (beyond the cut-off, a lower bound of it), the law's inflection (strongest attraction) and r0.
  KOKKOS_INLINE_FUNCTION double gap(const double x[3]) const
  {
    if (substrate.distance_bound(x) > law.r_cut) return substrate.distance_bound(x);
    contact::SurfacePoint p;
    substrate.project(x, p);
    return p.distance;
  }
  KOKKOS_INLINE_FUNCTION double inflection() const { return law.strongest_attraction_gap(); }
  KOKKOS_INLINE_FUNCTION double range() const { return law.r0; }

  KOKKOS_INLINE_FUNCTION bool evaluate(const double[3], const double x[3], double& phi, double gradient[3],
                                       double (*H)[3]) const
  {
    if (substrate.distance_bound(x) > law.r_cut) {   // certainly beyond the cut-off: no projection needed
      double d1, d2;
      law.evaluate(law.r_cut * 2.0, phi, d1, d2);
      for (int i = 0; i < 3; ++i) {
        gradient[i] = 0.0;
        if (H)
          for (int j = 0; j < 3; ++j) H[i][j] = 0.0;
      }
      return false;
    }
    contact::SurfacePoint p;
    substrate.project(x, p);
    double d1, d2;
    const bool active = law.evaluate(p.distance, phi, d1, d2);
    for (int i = 0; i < 3; ++i) gradient[i] = d1 * p.normal[i];
    if (H)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          H[i][j] = d2 * p.normal[i] * p.normal[j] + (curved ? d1 * p.curvature[i][j] : 0.0);
    return active;
  }
};

// Stiction on a flat substrate (laws/stiction.hpp).
struct StictionIntegrand {
  contact::StictionLaw law;
  static constexpr bool tangential = true;   // holds the pad along the substrate
  KOKKOS_INLINE_FUNCTION double far_bound(const double x[3]) const { return x[2] - law.substrate_height; }
  KOKKOS_INLINE_FUNCTION double cut_off() const { return law.law.r_cut; }
  KOKKOS_INLINE_FUNCTION double gap(const double x[3]) const { return x[2] - law.substrate_height; }
  KOKKOS_INLINE_FUNCTION double inflection() const { return law.law.strongest_attraction_gap(); }
  KOKKOS_INLINE_FUNCTION double range() const { return law.law.r0; }
  KOKKOS_INLINE_FUNCTION bool evaluate(const double anchor[3], const double x[3], double& phi, double gradient[3],
                                       double (*H)[3]) const
  {
    return law.evaluate(anchor, x, phi, gradient, H);
  }
};

struct ContactFaceResult {
  double energy = 0.0;
  double area = 0.0;        // undeformed area of the face
  int active_points = 0;    // quadrature points within the cut-off
  double dissipated = 0.0;  // a law with state: the energy dissipated on the face up to the trial state [nN nm]
};

// The history values an integrand keeps per quadrature point: its `history_size`, 0 where it declares none.
template <class Integrand, class = void>
struct HistorySize {
  static constexpr int value = 0;
};
template <class Integrand>
struct HistorySize<Integrand, std::void_t<decltype(Integrand::history_size)>> {
  static constexpr int value = Integrand::history_size;
};
// Whether an integrand's traction has a part along the substrate (its `tangential`; false where it declares none).
template <class Integrand, class = void>
struct Tangential : std::false_type {};
template <class Integrand>
struct Tangential<Integrand, std::void_t<decltype(Integrand::tangential)>>
    : std::integral_constant<bool, Integrand::tangential> {};
// Where an integrand with a history keeps the energy dissipated at a point [nN/nm]: its `dissipated_index`, -1 where
// it declares none.
template <class Integrand, class = void>
struct DissipatedIndex {
  static constexpr int value = -1;
};
template <class Integrand>
struct DissipatedIndex<Integrand, std::void_t<decltype(Integrand::dissipated_index)>> {
  static constexpr int value = Integrand::dissipated_index;
};
// Whether an integrand's Hessian is symmetric: its symmetric_tangent(), true where it declares none.
template <class Integrand, class = void>
struct DeclaresSymmetry : std::false_type {};
template <class Integrand>
struct DeclaresSymmetry<Integrand, std::void_t<decltype(std::declval<const Integrand&>().symmetric_tangent())>>
    : std::true_type {};
template <class Integrand>
bool symmetric_tangent(const Integrand& integrand)
{
  if constexpr (DeclaresSymmetry<Integrand>::value) return integrand.symmetric_tangent();
  else return true;
}

// Whether an integrand names another for the energy descents of jumps (its descent_integrand(), used where
// descends_on_another_energy() says so).
template <class Integrand, class = void>
struct DeclaresDescent : std::false_type {};
template <class Integrand>
struct DeclaresDescent<Integrand, std::void_t<decltype(std::declval<const Integrand&>().descent_integrand())>>
    : std::true_type {};

// Quadrature point (a, b) of a face's order x order Gauss rule: its shape functions, reference position X, anchor A
// and undeformed area element dA, and its current position for nodal displacements u.
template <class Surface>
struct FacePoint {
  double shape[Surface::nodes];
  double X[3] = {0, 0, 0}, A[3] = {0, 0, 0};
  double dA = 0.0;

  KOKKOS_INLINE_FUNCTION FacePoint(int order, int a, int b, const double Xn[Surface::nodes][3],
                                   const double An[Surface::nodes][3])
  {
    double s, t, ws, wt, dshape[Surface::nodes][2];
    elements::gauss_point(order, a, s, ws);
    elements::gauss_point(order, b, t, wt);
    Surface::evaluate(s, t, shape, dshape);
    for (int k = 0; k < Surface::nodes; ++k)
      for (int i = 0; i < 3; ++i) {
        X[i] += shape[k] * Xn[k][i];
        A[i] += shape[k] * An[k][i];
      }
    dA = elements::area_element<Surface>(dshape, Xn) * ws * wt;
  }
  // (Xn: the nodes' reference positions the point was made with.)
  KOKKOS_INLINE_FUNCTION void position(const double Xn[Surface::nodes][3], const double u[Surface::nodes][3],
                                       double x[3]) const
  {
    for (int i = 0; i < 3; ++i) x[i] = 0.0;
    for (int k = 0; k < Surface::nodes; ++k)
      for (int i = 0; i < 3; ++i) x[i] += shape[k] * (Xn[k][i] + u[k][i]);
  }
};

// One contact face with nodal anchors A: energy, residual r[3N] and (if K) tangent K[3N][3N]; for a law with state,
// the points' histories in (nullptr: all zero, the undeformed start) and their trial histories out (nullptr: not kept).
template <class Surface, class Integrand>
KOKKOS_INLINE_FUNCTION ContactFaceResult contact_face(const Integrand& integrand, const double X[Surface::nodes][3],
                                                      const double A[Surface::nodes][3],
                                                      const double u[Surface::nodes][3], int order,
                                                      double r[3 * Surface::nodes],
                                                      double (*K)[3 * Surface::nodes] = nullptr,
                                                      const double* history = nullptr, double* trial = nullptr)
{
  constexpr int N = Surface::nodes;
  constexpr int kept = HistorySize<Integrand>::value;
  ContactFaceResult result;
  for (int p = 0; p < 3 * N; ++p) {
    r[p] = 0.0;
    if (K)
      for (int q = 0; q < 3 * N; ++q) K[p][q] = 0.0;
  }
  for (int a = 0; a < order; ++a)
    for (int b = 0; b < order; ++b) {
      const FacePoint<Surface> point(order, a, b, X, A);
      const auto& shape = point.shape;
      const double dA = point.dA;
      double xq[3];
      point.position(X, u, xq);
      double phi, gradient[3], H[3][3];
      bool active;
      if constexpr (kept > 0) {
        const double start[kept] = {};
        double out[kept];
        const int index = (a * order + b) * kept;
        active = integrand.evaluate(point.A, xq, history ? history + index : start, out, phi, gradient,
                                    K ? H : nullptr);
        result.dissipated += Integrand::dissipated(out) * dA;
        if (trial)
          for (int k = 0; k < kept; ++k) trial[index + k] = out[k];
      } else {
        active = integrand.evaluate(point.A, xq, phi, gradient, K ? H : nullptr);
      }
      result.energy += phi * dA;
      result.area += dA;
      if (!active) continue;
      ++result.active_points;
      for (int k = 0; k < N; ++k)
        for (int i = 0; i < 3; ++i) r[3 * k + i] += shape[k] * gradient[i] * dA;
      if (K)
        for (int k = 0; k < N; ++k)
          for (int l = 0; l < N; ++l) {
            const double w = shape[k] * shape[l] * dA;
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j) K[3 * k + i][3 * l + j] += w * H[i][j];
          }
    }
  return result;
}

// The quadrature points of one face whose gap under a displacement change u_from -> u_to crosses the law's inflection
// (the strongest attraction, where the law's stiffness changes sign): the limiting points of a Newton step at the
// peel front. Adds to sums[0..9]: their count, the count of points whose gap changes by more than `large` (nm), the
// crossing points' reference X, Y, X^2 and Y^2, and their share of the adhesion energy's change along the step,
// sum phi(x(t)) dA - phi(x(0)) dA at t = 0.25, 0.5, 0.75, 1 (x(t) = x_from + t (x_to - x_from)); and to sums[10..11]
// the points still adhering at `to` (gap below the inflection): their undeformed area and the integral of their travel
// along the substrate's plane (X, Y), sum |x_to - x_from|_XY dA, how far the held part of the pad has slid. Points
// beyond the cut-off at both ends are not looked at.
constexpr int gap_change_sums = 12;
template <class Surface, class Integrand>
KOKKOS_INLINE_FUNCTION void face_gap_changes(const Integrand& integrand, const double X[Surface::nodes][3],
                                             const double A[Surface::nodes][3],
                                             const double u_from[Surface::nodes][3],
                                             const double u_to[Surface::nodes][3], int order, double large,
                                             double sums[gap_change_sums])
{
  const double inflection = integrand.inflection();
  for (int a = 0; a < order; ++a)
    for (int b = 0; b < order; ++b) {
      const FacePoint<Surface> point(order, a, b, X, A);
      double from[3], to[3];
      point.position(X, u_from, from);
      point.position(X, u_to, to);
      const double g_from = integrand.gap(from), g_to = integrand.gap(to);
      if (g_from > integrand.cut_off() && g_to > integrand.cut_off()) continue;
      if (::fabs(g_to - g_from) > large) sums[1] += 1.0;
      if (g_to < inflection) {
        sums[10] += point.dA;
        sums[11] += ::sqrt((to[0] - from[0]) * (to[0] - from[0]) + (to[1] - from[1]) * (to[1] - from[1])) * point.dA;
      }
      if ((g_from - inflection) * (g_to - inflection) >= 0.0) continue;
      sums[0] += 1.0;
      sums[2] += point.X[0];
      sums[3] += point.X[1];
      sums[4] += point.X[0] * point.X[0];
      sums[5] += point.X[1] * point.X[1];
      double phi_from, phi, gradient[3];
      integrand.evaluate(point.A, from, phi_from, gradient, nullptr);
      for (int k = 1; k <= 4; ++k) {
        const double f = 0.25 * k;
        const double x[3] = {from[0] + f * (to[0] - from[0]), from[1] + f * (to[1] - from[1]),
                             from[2] + f * (to[2] - from[2])};
        integrand.evaluate(point.A, x, phi, gradient, nullptr);
        sums[5 + k] += (phi - phi_from) * point.dA;
      }
    }
}

// The points of one face that a displacement change u_from -> u_to carries outward past the gap `limit` (nm): the
// peel front's points the step would release. Sets r[3N] to the integral over them of their gap's gradient with
// respect to the face's nodal displacements (sum dg/du dA) and adds to sums[0..1] their count and sum (limit -
// g_from) dA: the row c and target t of the constraint c . du = t that brings them, in the integral, to `limit`.
constexpr int gap_limit_sums = 2;
template <class Surface, class Integrand>
KOKKOS_INLINE_FUNCTION void face_gap_limit(const Integrand& integrand, const double X[Surface::nodes][3],
                                           const double A[Surface::nodes][3], const double u_from[Surface::nodes][3],
                                           const double u_to[Surface::nodes][3], int order, double limit,
                                           double r[3 * Surface::nodes], double sums[gap_limit_sums])
{
  constexpr int N = Surface::nodes;
  for (int p = 0; p < 3 * N; ++p) r[p] = 0.0;
  for (int a = 0; a < order; ++a)
    for (int b = 0; b < order; ++b) {
      const FacePoint<Surface> point(order, a, b, X, A);
      double from[3], to[3];
      point.position(X, u_from, from);
      point.position(X, u_to, to);
      const double g_from = integrand.gap(from), g_to = integrand.gap(to);
      if (!(g_from < limit && g_to > limit)) continue;
      sums[0] += 1.0;
      sums[1] += (limit - g_from) * point.dA;
      // dg/dx by central differences (a flat substrate's gap is linear in x, a rough one's smooth)
      constexpr double h = 1e-4;   // nm
      double normal[3];
      for (int i = 0; i < 3; ++i) {
        double plus[3] = {from[0], from[1], from[2]}, minus[3] = {from[0], from[1], from[2]};
        plus[i] += h;
        minus[i] -= h;
        normal[i] = (integrand.gap(plus) - integrand.gap(minus)) / (2.0 * h);
      }
      for (int k = 0; k < N; ++k)
        for (int i = 0; i < 3; ++i) r[3 * k + i] += point.shape[k] * normal[i] * point.dA;
    }
}

// The same with the anchors at the reference positions.
template <class Surface, class Integrand>
KOKKOS_INLINE_FUNCTION ContactFaceResult contact_face(const Integrand& integrand, const double X[Surface::nodes][3],
                                                      const double u[Surface::nodes][3], int order,
                                                      double r[3 * Surface::nodes],
                                                      double (*K)[3 * Surface::nodes] = nullptr)
{
  return contact_face<Surface>(integrand, X, X, u, order, r, K);
}

}  // namespace spatula::contact
