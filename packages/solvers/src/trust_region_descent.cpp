// The energy minimizer's trust-region method (MinimizerParameters::Method::trust_region).
//
// Each iteration assembles the tangent K at x and takes the step p of the Steihaug-Toint truncated conjugate
// gradients on the quadratic model m(p) = g.p + p.K.p / 2 within |p|_M <= radius (Steihaug, SIAM J. Numer. Anal. 20,
// 1983; Conn, Gould and Toint, Trust-Region Methods, 2000, section 7.5): M is the preconditioner, kept LDL^T factors
// of a positive definite shifted tangent K' + eta I from an earlier state; along a direction of negative curvature
// the step goes to the region's boundary, so a snap is followed without shifting the tangent at every iteration.
// The step is taken where Pi falls by at least a small share of what the model predicts; the radius shrinks after a
// poor prediction and doubles after a good one that reached the boundary. The factors are renewed only when the
// conjugate gradients stop converging within their limit (their preconditioner no longer fits the tangent).
//
// The assembled matrix is K + eta I (the proximal shift of the factors, anchored at x: f is unchanged), so products
// with K are those with the matrix less eta v (eta is not added on prescribed rows, where every vector here is 0).
#include "solvers/descent_state.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>

namespace spatula::solvers {

namespace {

using discretization::Vector;

constexpr int most_conjugate_gradients = 60;   // per iteration; reaching it renews the factors
constexpr double accepted_share = 1e-4;        // of the model's decrease, for a step to be taken

// tau >= 0 with |p + tau d|_M = radius, from p.M.p, p.M.d, d.M.d.
double to_boundary(double pMp, double pMd, double dMd, double radius)
{
  const double discriminant = std::max(0.0, pMd * pMd + dMd * (radius * radius - pMp));
  return (-pMd + std::sqrt(discriminant)) / dMd;
}

}  // namespace

std::optional<std::string> EnergyMinimizer::descend_by_trust_region(Vector& x, Descent& d, double small_gradient,
                                                                     const Watch& watch)
{
  auto& system = model_.system();
  auto g = system.create_vector(), r = system.create_vector(), z = system.create_vector();
  auto p = system.create_vector(), direction = system.create_vector(), product = system.create_vector();
  auto trial = system.create_vector();
  const auto tangent_times = [&](const Vector& v, Vector& out) {   // K v = (K + eta I) v - eta v
    system.jacobian()->apply(v, out);
    if (d.eta > 0.0) out.update(-d.eta, v, 1.0);
  };
  for (; d.iteration < parameters_.maximum_iterations; watch ? watch(x, d.progress()) : void(), ++d.iteration) {
    // The state, its gradient g = f and the tangent (shifted by the factors' eta) at x; fresh factors where none
    // are kept, the shift raised until they are positive definite.
    const bool fresh = !d.preconditioned;
    const auto point = evaluate(x, d, true, fresh, *g);
    if (!point.admissible) return std::string("an element inverted during the energy descent");
    if (fresh) {
      if (point.negative_pivots > 0) {
        d.row(tables_, point.negative_pivots, point.residual, 0.0, point.energy);
        ++d.indefinite;
        if (auto stop = d.stiffen(parameters_.shift_growth)) return stop;
        continue;
      }
    } else {
      solver().count_reuse();   // an iteration preconditioned by kept factors
    }
    d.preconditioned = true;
    d.residual = point.residual;
    report_progress(d, point.residual, point.energy);
    if (point.residual < small_gradient) {   // the confirmation decides
      d.row(tables_, fresh ? 0 : -1, point.residual, 0.0, point.energy);
      return std::nullopt;
    }

    // Steihaug-Toint: conjugate gradients on K p = -g from p = 0, preconditioned by M, truncated at the boundary.
    p->putScalar(0.0);
    r->update(-1.0, *g, 0.0);
    solver().apply(*r, *z);
    direction->assign(*z);
    double rz = r->dot(*z);
    if (!std::isfinite(d.radius)) d.radius = std::sqrt(rz);   // the preconditioned gradient's length
    double pMp = 0.0, pMd = 0.0, dMd = rz;
    const double stop = std::min(0.5, std::sqrt(point.residual)) * point.residual;   // superlinear near the minimum
    bool boundary = false, converged = false;
    int iterations = 0;
    for (; iterations < most_conjugate_gradients && !boundary && !converged; ++iterations) {
      tangent_times(*direction, *product);
      const double curvature = direction->dot(*product);
      if (curvature <= 0.0) {   // negative curvature: to the boundary along it
        p->update(to_boundary(pMp, pMd, dMd, d.radius), *direction, 1.0);
        boundary = true;
        break;
      }
      const double alpha = rz / curvature;
      const double next_pMp = pMp + 2.0 * alpha * pMd + alpha * alpha * dMd;
      if (next_pMp >= d.radius * d.radius) {   // the full conjugate-gradient step leaves the region
        p->update(to_boundary(pMp, pMd, dMd, d.radius), *direction, 1.0);
        boundary = true;
        break;
      }
      p->update(alpha, *direction, 1.0);
      r->update(-alpha, *product, 1.0);
      pMp = next_pMp;
      if (r->norm2() <= stop) {
        converged = true;
        break;
      }
      solver().apply(*r, *z);
      const double next_rz = r->dot(*z);
      const double beta = next_rz / rz;
      rz = next_rz;
      pMd = beta * (pMd + alpha * dMd);
      dMd = rz + beta * beta * dMd;
      direction->update(1.0, *z, beta);
    }
    // The model's decrease -(g.p + p.K.p / 2) against Pi's.
    tangent_times(*p, *product);
    const double predicted = -(g->dot(*p) + 0.5 * p->dot(*product));
    trial->update(1.0, x, 1.0, *p, 0.0);
    const auto at_trial = system.evaluate(*trial, nullptr, false);
    const double actual = at_trial.admissible ? point.energy - at_trial.energy() : -1.0;
    const double ratio = predicted > 0.0 && at_trial.admissible ? actual / predicted : -1.0;
    const double length = std::sqrt(std::max(0.0, pMp));
    if (tables_)
      d.table << "  trust    " << std::setw(9) << d.iteration << "  " << std::setw(9) << d.eta / d.scale << "  "
              << std::setw(7) << (fresh ? 0 : -1) << "  " << std::setw(9) << point.residual
              << "  " << std::setw(9) << ratio << "  " << std::setprecision(8) << point.energy << std::setprecision(2)
              << "  cg " << iterations << (boundary ? " boundary" : "") << "  radius " << d.radius << "\n";
    // A poor prediction shrinks the region to a quarter (of the step that missed, if shorter); a good one at the
    // boundary doubles it. (Widening it fourfold, or extending a good boundary step along its direction while Pi
    // falls, took as many iterations or more on the medium pull-off's snap: the next boundary step then missed.)
    if (ratio < 0.25) d.radius = 0.25 * (boundary ? d.radius : std::min(d.radius, length));
    else if (ratio > 0.75 && boundary) d.radius *= 2.0;
    if (ratio > accepted_share) {
      x.assign(*trial);
      ++d.accepted;
    } else {
      ++d.no_decrease;
    }
    if (!converged && !boundary) {   // the factors no longer precondition this tangent: fresh ones next
      d.preconditioned = false;
      d.eta *= 0.25;   // (raised again if the tangent there is indefinite)
      if (d.eta < 1e-9 * d.scale) d.eta = 0.0;
    }
    if (d.radius < 1e-14 * std::max(1.0, x.normInf()))
      return "the trust region shrank to rounding size at iteration " + std::to_string(d.iteration) + " (" +
             std::to_string(d.no_decrease) + " steps without decrease): no descent from this state";
  }
  return std::nullopt;
}

}  // namespace spatula::solvers
