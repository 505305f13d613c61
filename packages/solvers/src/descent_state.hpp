#pragma once
// The state of one energy minimization, shared by its methods (energy_minimizer.cpp: shifted Newton;
// trust_region_descent.cpp: trust region): the tangent's shift, where the iterations went, the factors' cycle,
// and the iterations' table. Private to the minimizer's files.
#include "solvers/energy_minimizer.hpp"
#include "solvers/renewal_rule.hpp"
#include "solvers/wall_clock.hpp"

#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

namespace spatula::solvers {

// The state of one minimization: the shift eta of the tangent (relative to `scale`, the mean diagonal), where its
// iterations went (for the diagnosis of a descent that does not settle) and their table.
struct EnergyMinimizer::Descent {
  double eta = 0.0, scale = 0.0;
  int iteration = 0;
  int indefinite = 0, no_decrease = 0, accepted = 0;
  bool unshifted_tried = false;   // at the current state, with a small gradient
  int kept = 0;                   // further iterations the current (positive definite) factors may serve
  RenewalRule cost;               // refactor = cost: the current factors' cycle
  double cycle_began = 0.0;       // when fresh factors were last asked for (set as each descent call begins)
  double residual = 0.0;          // |f| at the last iteration [nN]
  double began = now(), reported = now();   // a progress line at least every minute of a long descent
  // Trust region: the radius (in the preconditioner's norm; infinite until the first step sets it) and whether
  // the kept factors are those of a positive definite shifted tangent to precondition with.
  double radius = std::numeric_limits<double>::infinity();
  bool preconditioned = false;
  std::ostringstream table;

  DescentProgress progress() const { return {eta, scale, iteration + 1}; }
  // The kept factors are given up: a new cycle begins.
  void refactor()
  {
    kept = 0;
    cycle_began = now();
  }
  // A stiffer shift (the tangent was indefinite, or Pi did not decrease along its direction); why the descent stops
  // once the shift has passed the largest.
  std::optional<std::string> stiffen(double growth)
  {
    eta = eta == 0.0 ? 1e-6 * scale : growth * eta;
    if (shift_exhausted()) return exhausted_reason();
    return std::nullopt;
  }
  // A shift this far above the tangent's mean diagonal leaves a steepest descent with steps of rounding size: no
  // tangent of a body that is still connected is that indefinite, so the descent stops instead of growing it further.
  static constexpr double largest_shift = 1e10;
  bool shift_exhausted() const { return eta > largest_shift * scale; }
  std::string exhausted_reason() const
  {
    std::ostringstream reason;
    reason << "the energy descent's shift passed " << largest_shift << " x the tangent's mean diagonal at iteration "
           << iteration << " (" << indefinite << " shifts for an indefinite tangent, " << no_decrease
           << " for no decrease of Pi): no descent direction exists at this state";
    return reason.str();
  }

  void row(bool tables, int negative, double residual_norm, double step, double energy)
  {
    if (!tables) return;
    table << "  descent  " << std::setw(9) << iteration << "  " << std::setw(9) << eta / scale << "  " << std::setw(7)
          << negative << "  " << std::setw(9) << residual_norm << "  " << std::setw(9) << step << "  "
          << std::setprecision(8) << energy << std::setprecision(2) << "\n";
  }
};

// One descent iteration's state at x: residual f, Pi, |f| and, with fresh factors (the tangent shifted by the
// descent's eta, factored), the negative pivots of their inertia.
struct EnergyMinimizer::Point {
  bool admissible;
  double energy, residual;
  int negative_pivots;
};

}  // namespace spatula::solvers
