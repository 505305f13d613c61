// The energy line search on lines whose minimum is known: a parabola (the secant on the slope is exact), a quartic
// (Newton's step falls short by a factor 3 at every iteration: full steps converge linearly), an inadmissible part
// of the line and the longest step.
#include "solvers/energy_line_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using spatula::solvers::EnergyLineSearchParameters;
using spatula::solvers::LinePoint;
using spatula::solvers::search_energy_line;

// phi(alpha) = (alpha - minimum)^2 / 2, admissible up to `admissible_to`; counts its evaluations.
struct Parabola {
  double minimum;
  double admissible_to = std::numeric_limits<double>::infinity();
  int evaluations = 0;
  LinePoint operator()(double step)
  {
    ++evaluations;
    return {step, step - minimum, 0.5 * (step - minimum) * (step - minimum), step <= admissible_to};
  }
  LinePoint origin() const { return {0.0, -minimum, 0.5 * minimum * minimum, true}; }
};

TEST(EnergyLineSearch, NewtonsStepAtTheMinimumCostsOneResidual)
{
  Parabola line{1.0};
  const auto point = search_energy_line(std::ref(line), line.origin(), {});
  EXPECT_DOUBLE_EQ(point.step, 1.0);
  EXPECT_EQ(line.evaluations, 1);
}

TEST(EnergyLineSearch, ExtrapolatesAShortNewtonStepToTheMinimum)
{
  Parabola line{3.0};   // 1, then 2 (at most doubling), then the secant's 3
  const auto point = search_energy_line(std::ref(line), line.origin(), {});
  EXPECT_NEAR(point.step, 3.0, 1e-12);
  EXPECT_EQ(line.evaluations, 3);
}

TEST(EnergyLineSearch, CutsANewtonStepThatOvershoots)
{
  Parabola line{0.5};
  const auto point = search_energy_line(std::ref(line), line.origin(), {});
  EXPECT_NEAR(point.step, 0.5, 1e-12);
  EXPECT_EQ(line.evaluations, 2);
}

TEST(EnergyLineSearch, StaysOnTheAdmissiblePart)
{
  Parabola line{3.0, 1.6};   // 1, 2 (inadmissible), 1.5, then 1.75 (inadmissible): the best admissible is 1.5
  const auto point = search_energy_line(std::ref(line), line.origin(), {});
  EXPECT_TRUE(point.admissible);
  EXPECT_DOUBLE_EQ(point.step, 1.5);
  EXPECT_EQ(line.evaluations, 4);
}

TEST(EnergyLineSearch, StopsAtTheLongestStep)
{
  Parabola line{10.0};
  EnergyLineSearchParameters parameters;
  parameters.maximum_evaluations = 10;
  const auto point = search_energy_line(std::ref(line), line.origin(), parameters);
  EXPECT_DOUBLE_EQ(point.step, parameters.maximum_step);
  EXPECT_EQ(line.evaluations, 3);   // 1, 2, 4
}

TEST(EnergyLineSearch, NothingAdmissibleIsSaid)
{
  Parabola line{1.0, 0.01};
  const auto point = search_energy_line(std::ref(line), line.origin(), {});
  EXPECT_FALSE(point.admissible);
  EXPECT_EQ(line.evaluations, 4);
}

// Newton on Pi(x) = x^4 / 4 (a minimum where the tangent 3 x^2 vanishes, as at a fold): the step -x / 3 leaves 2/3 of
// the error, so full steps need 46 iterations from x = 1 to |x| < 1e-8. Along the line the energy's minimum is at
// alpha = 3 and phi'(alpha) = phi'(0) (1 - alpha / 3)^3; the search stops once |phi'| has fallen to a quarter of
// its start, so each iteration leaves at most 0.25^(1/3) = 0.63 of the error: at most 40 iterations.
TEST(EnergyLineSearch, NewtonAtADegenerateMinimumConvergesFasterThanWithFullSteps)
{
  const auto newton_iterations = [](bool line_search) {
    double x = 1.0;
    int iterations = 0;
    for (; std::abs(x) >= 1e-8 && iterations < 1000; ++iterations) {
      const double direction = -x / 3.0;   // -f / f' with f = x^3
      double step = 1.0;
      if (line_search) {
        const auto line = [&](double alpha) {
          const double y = x + alpha * direction;
          return LinePoint{alpha, y * y * y * direction, 0.25 * y * y * y * y, true};
        };
        const LinePoint origin{0.0, x * x * x * direction, 0.25 * x * x * x * x, true};
        const auto point = search_energy_line(line, origin, {});
        EXPECT_LE(point.energy, 0.25 * std::pow(x + direction, 4));   // never worse than Newton's step
        step = point.step;
      }
      x += step * direction;
    }
    return iterations;
  };
  EXPECT_EQ(newton_iterations(false), 46);
  EXPECT_LE(newton_iterations(true), 40);
}

}  // namespace

namespace {

using spatula::solvers::search_energy_decrease;

// The minimizer's search on the parabola: from alpha = 1 it doubles while the energy keeps falling and keeps the
// lowest point (2, since phi(4) = phi(2) is no lower), and halves a step that overshoots to the first sufficient one.
TEST(EnergyDecreaseSearch, ExpandsWhileTheEnergyFallsAndHalvesAnOvershoot)
{
  Parabola far{3.0};
  auto point = search_energy_decrease(std::ref(far), far.origin());
  EXPECT_DOUBLE_EQ(point.step, 2.0);
  EXPECT_DOUBLE_EQ(point.energy, 0.5);
  EXPECT_EQ(far.evaluations, 3);   // 1, 2, 4
  Parabola near{0.3};   // phi(1) = 0.245 > phi(0) = 0.045; phi(0.5) = 0.02 is sufficient, and short of 1: kept
  point = search_energy_decrease(std::ref(near), near.origin());
  EXPECT_DOUBLE_EQ(point.step, 0.5);
  EXPECT_EQ(near.evaluations, 2);
}

// Along a direction of negative curvature (phi = -alpha^2 - alpha) the expansion goes on to its longest step, 64;
// an inadmissible part ends it at the last admissible doubling; with no sufficient decrease anywhere (a rising line
// whose slope at 0 is said to be negative) the origin comes back, with step 0, after 30 evaluations.
TEST(EnergyDecreaseSearch, StopsAtTheLongestStepTheAdmissiblePartOrNowhere)
{
  int evaluations = 0;
  const auto concave = [&](double step) {
    ++evaluations;
    return LinePoint{step, -2.0 * step - 1.0, -step * step - step, step <= 5.0};
  };
  auto point = search_energy_decrease(concave, {0.0, -1.0, 0.0, true});
  EXPECT_DOUBLE_EQ(point.step, 4.0);   // 8 is inadmissible
  const auto unbounded = [](double step) { return LinePoint{step, -2.0 * step - 1.0, -step * step - step, true}; };
  point = search_energy_decrease(unbounded, {0.0, -1.0, 0.0, true});
  EXPECT_DOUBLE_EQ(point.step, 64.0);
  evaluations = 0;
  const auto rising = [&](double step) {
    ++evaluations;
    return LinePoint{step, 1.0, step, true};
  };
  point = search_energy_decrease(rising, {0.0, -1.0, 0.0, true});
  EXPECT_EQ(point.step, 0.0);
  EXPECT_EQ(point.energy, 0.0);
  EXPECT_EQ(evaluations, 30);
}

}  // namespace
