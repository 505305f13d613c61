#pragma once
// The line searches on the energy Pi along a direction d, phi(alpha) = Pi(x + alpha d): Newton's (the zero of the
// slope) and the energy minimizer's (sufficient decrease, with expansion).
//
// Newton's: a line search on the energy along Newton's direction, for problems with a potential Pi (f = dPi/dx): it looks for
// the zero of the energy's slope  phi'(alpha) = f(x + alpha d) . d  on 0 < alpha <= maximum step, extrapolating past
// Newton's step alpha = 1 as well as cutting it. Where a front of contact faces moves, Newton's step falls short
// along the line (phi'(1) / phi'(0) near 1: the tangent stiffens ahead of the front) and full steps converge
// linearly; a longer step along the same direction costs residuals, not tangents.
#include <functional>

namespace spatula::solvers {

// One point of the line: the step alpha, the slope phi'(alpha), the energy phi(alpha); admissible false where no
// state exists (an element inverted).
struct LinePoint {
  double step = 0.0;
  double slope = 0.0;
  double energy = 0.0;
  bool admissible = true;
};

struct EnergyLineSearchParameters {
  double accept = 0.25;        // stop once |phi'(alpha)| <= accept |phi'(0)|
  double maximum_step = 4.0;   // the longest step, in Newton steps
  int maximum_evaluations = 4; // residuals per search, Newton's step included
};

// Searches from phi(0) = origin.energy, phi'(0) = origin.slope < 0 (a descent direction): evaluates alpha = 1 first
// and keeps it when its slope is small enough; else secant steps on phi' within the bracket [last alpha with
// phi' < 0, first with phi' > 0], doubling (at most) while no point with phi' > 0 is known, halving towards the last
// admissible point past an inadmissible one. Returns the point whose slope was accepted, else the admissible point
// of lowest energy among those evaluated, else the origin marked inadmissible. `evaluate` computes one point; the
// caller's state is the last point evaluated.
LinePoint search_energy_line(const std::function<LinePoint(double step)>& evaluate, const LinePoint& origin,
                             const EnergyLineSearchParameters& parameters);

// The energy minimizer's: Armijo's sufficient decrease phi(alpha) <= phi(0) + 1e-4 alpha phi'(0), tried from
// alpha = 1, halved while not met (at most 30 evaluations in all), and doubled while it is met with a lower phi (up
// to alpha = 64: along a direction of negative curvature going further lowers Pi more). Needs only energies (slope
// of `origin`: phi'(0) < 0). Returns the sufficient point of lowest energy, or the origin (step 0) if none.
LinePoint search_energy_decrease(const std::function<LinePoint(double step)>& evaluate, const LinePoint& origin);

}  // namespace spatula::solvers
