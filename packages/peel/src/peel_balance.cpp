#include "peel/peel_balance.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>

namespace spatula::peel {

namespace {

// The root of an increasing function on [low, high] (f(low) <= 0 <= f(high)) by bisection, to round-off.
double increasing_root(const std::function<double(double)>& f, double low, double high)
{
  for (int k = 0; k < 200 && high - low > 1e-15 * std::abs(high); ++k) {
    const double middle = 0.5 * (low + high);
    (f(middle) > 0.0 ? high : low) = middle;
  }
  return 0.5 * (low + high);
}

struct Evaluated {
  double energy, P[3][3];
};

Evaluated evaluate(const laws::NeoHookean& law, double stretch, double lateral)
{
  const double F[3][3] = {{stretch, 0.0, 0.0}, {0.0, lateral, 0.0}, {0.0, 0.0, lateral}};
  Evaluated e{};
  if (!law.evaluate(F, e.energy, e.P))
    throw std::invalid_argument("uniaxial_tension: stretch " + std::to_string(stretch) + " inverts the bar");
  return e;
}

}  // namespace

UniaxialState uniaxial_tension(const laws::NeoHookean& law, double stretch)
{
  if (!(stretch > 0.0)) throw std::invalid_argument("uniaxial_tension: the stretch must be positive");
  // P_22 grows with the lateral stretch: from negative (squeezed) to positive (pulled sideways).
  const double lateral =
      increasing_root([&](double m) { return evaluate(law, stretch, m).P[1][1]; }, 1e-3, 1e3);
  const auto e = evaluate(law, stretch, lateral);
  return {stretch, lateral, e.energy, e.P[0][0]};
}

double uniaxial_stretch(const laws::NeoHookean& law, double stress)
{
  if (stress < 0.0) throw std::invalid_argument("uniaxial_stretch: only tension (stress >= 0)");
  double high = 1.0;
  while (uniaxial_tension(law, high).stress < stress) {
    high *= 1.5;
    if (high > 100.0) throw std::invalid_argument("uniaxial_stretch: stress beyond the law's uniaxial range");
  }
  return increasing_root([&](double l) { return uniaxial_tension(law, l).stress - stress; }, 1.0, high);
}

double steady_peel_force(const laws::NeoHookean& law, const StripSection& section, double work_of_adhesion,
                         double angle, double pre_stretch)
{
  const double area = section.width * section.thickness;
  const auto adhered = uniaxial_tension(law, pre_stretch);
  const double bond = work_of_adhesion * section.width;   // per reference length, however stretched
  const double back = pre_stretch * std::cos(angle);   // the front's retreat along the pull, per dS
  // The balance's surplus at arm stretch l: grows with l wherever l > lambda_0 cos theta.
  const auto surplus = [&](double l) {
    const auto arm = uniaxial_tension(law, l);
    return area * arm.stress * (l - back) - area * (arm.energy - adhered.energy) - bond;
  };
  // The larger root (Chen, Wu and Gao's peel-off force): above the surplus' minimum at lambda_0 cos theta.
  const double low = std::max(1.0, back);
  if (surplus(low) >= 0.0) return 0.0;   // no pull holds the front
  double high = low + 1e-3;
  while (surplus(high) < 0.0) {
    high = 1.0 + 2.0 * (high - 1.0);
    if (high > 10.0) throw std::invalid_argument("steady_peel_force: no balance below a stretch of 10");
  }
  const double stretch = increasing_root(surplus, low, high);
  return area * uniaxial_tension(law, stretch).stress / section.width;
}

}  // namespace spatula::peel
