#include "solvers/energy_line_search.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace spatula::solvers {

LinePoint search_energy_line(const std::function<LinePoint(double step)>& evaluate, const LinePoint& origin,
                             const EnergyLineSearchParameters& parameters)
{
  const double accepted_slope = parameters.accept * std::abs(origin.slope);
  LinePoint below = origin, before_below = origin;   // the last two points with phi' < 0
  std::optional<LinePoint> above;                     // the first point with phi' >= 0
  double inadmissible_from = parameters.maximum_step * 2.0;
  std::optional<LinePoint> best;   // the admissible point of lowest energy
  double step = 1.0;
  for (int evaluation = 0; evaluation < parameters.maximum_evaluations; ++evaluation) {
    const LinePoint point = evaluate(step);
    if (!point.admissible) {
      inadmissible_from = step;
      step = 0.5 * (below.step + step);
      continue;
    }
    if (!best || point.energy < best->energy) best = point;
    if (std::abs(point.slope) <= accepted_slope) return point;
    if (point.slope < 0.0) {
      before_below = below;
      below = point;
    } else if (!above || point.step < above->step) {
      above = point;
    }
    const double limit = std::min(parameters.maximum_step, inadmissible_from);
    if (above) {   // the minimum is bracketed: a secant step, kept off the bracket's ends
      const double width = above->step - below.step;
      const double secant = below.step - below.slope * width / (above->slope - below.slope);
      step = std::clamp(secant, below.step + 0.1 * width, above->step - 0.1 * width);
    } else {       // still descending: extrapolate the slope to zero, at most doubling the step
      if (below.step >= limit) break;
      const double rise = below.slope - before_below.slope;
      const double secant = rise > 0.0 ? below.step - below.slope * (below.step - before_below.step) / rise
                                       : 2.0 * below.step;
      const double upper = inadmissible_from <= parameters.maximum_step ? 0.5 * (below.step + inadmissible_from)
                                                                         : std::min(2.0 * below.step, limit);
      step = std::clamp(secant, std::min(1.1 * below.step, upper), upper);
    }
  }
  if (best) return *best;
  LinePoint none = origin;   // nothing evaluated was admissible
  none.admissible = false;
  return none;
}

LinePoint search_energy_decrease(const std::function<LinePoint(double step)>& evaluate, const LinePoint& origin)
{
  LinePoint best = origin;
  best.step = 0.0;
  double step = 1.0;
  for (int evaluation = 0; evaluation < 30; ++evaluation) {
    const LinePoint point = evaluate(step);
    const bool sufficient = point.admissible && point.energy <= origin.energy + 1e-4 * step * origin.slope;
    if (sufficient && point.energy < best.energy) {
      best = point;
      best.step = step;
      if (step >= 1.0 && step < 64.0) {   // still descending: try further
        step *= 2.0;
        continue;
      }
      break;
    }
    if (best.step > 0.0) break;   // the expansion went too far: keep the best
    step *= 0.5;
  }
  return best;
}

}  // namespace spatula::solvers
