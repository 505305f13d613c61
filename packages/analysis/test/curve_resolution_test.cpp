// The step control's resolution of the reaction curve: the increment's bound from the curve's second difference, its
// floor, a new stretch after a jump or a gap in the samples, and the peak of a sampled
// parabola within the tolerance of the true one.
#include "analysis/step_control.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using spatula::analysis::CurveResolution;
using spatula::analysis::StepControllerState;

namespace {

constexpr double floor = 0.01;   // the stage's initial increment

// The parabola R(x) = top - a (x - peak)^2.
struct Parabola {
  double top = 5.0, a = 0.02, peak = 40.0;
  double operator()(double x) const { return top - a * (x - peak) * (x - peak); }
};

TEST(CurveResolution, BoundIsTheChordErrorOfTheCurvature)
{
  const Parabola curve;
  CurveResolution resolution;
  resolution.start(1e-3, floor);
  const double loads[3] = {0.0, 3.0, 7.0};   // unequal spacing: R'' = -2a exactly all the same
  for (int k = 0; k < 3; ++k) resolution.reached(k + 1, k, false, loads[k], curve(loads[k]));
  const double largest = std::abs(curve(0.0));   // 27 against 5 at the top: the largest |R| of the stage so far
  const double expected = std::sqrt(8.0 * 1e-3 * largest / (2.0 * curve.a));
  EXPECT_NEAR(resolution.limit(100.0), expected, 1e-12 * expected);
  EXPECT_DOUBLE_EQ(resolution.limit(0.5 * expected), 0.5 * expected);   // a shorter increment is kept
}

TEST(CurveResolution, OffWithoutToleranceOrThreeSamples)
{
  const Parabola curve;
  CurveResolution off;
  off.start(0.0, floor);
  for (int k = 0; k < 3; ++k) off.reached(k + 1, k, false, 2.0 * k, curve(2.0 * k));
  EXPECT_DOUBLE_EQ(off.limit(100.0), 100.0);
  CurveResolution two;
  two.start(1e-3, floor);
  for (int k = 0; k < 2; ++k) two.reached(k + 1, k, false, 2.0 * k, curve(2.0 * k));
  EXPECT_DOUBLE_EQ(two.limit(100.0), 100.0);
}

TEST(CurveResolution, AJumpOrAGapStartsANewStretch)
{
  const Parabola curve;
  CurveResolution jumped;
  jumped.start(1e-3, floor);
  for (int k = 0; k < 3; ++k) jumped.reached(k + 1, k, false, 2.0 * k, curve(2.0 * k));
  EXPECT_LT(jumped.limit(100.0), 100.0);
  jumped.reached(4, 3, true, 8.0, curve(8.0));   // the state after a snap: the curve is not continuous across it
  EXPECT_DOUBLE_EQ(jumped.limit(100.0), 100.0);
  jumped.reached(5, 4, false, 10.0, curve(10.0));
  jumped.reached(6, 5, false, 12.0, curve(12.0));
  EXPECT_LT(jumped.limit(100.0), 100.0);
  jumped.reached(9, 7, false, 14.0, curve(14.0));   // states 7 and 8 came from elsewhere (a jump's descent)
  EXPECT_DOUBLE_EQ(jumped.limit(100.0), 100.0);
}

TEST(CurveResolution, NeverBelowItsFloor)
{
  CurveResolution sharp;
  sharp.start(1e-6, floor);
  const double loads[3] = {0.0, 1.0, 2.0}, reactions[3] = {0.0, 1.0, -100.0};
  for (int k = 0; k < 3; ++k) sharp.reached(k + 1, k, false, loads[k], reactions[k]);
  EXPECT_DOUBLE_EQ(sharp.limit(100.0), floor);
}

TEST(CurveResolution, SavedSamplesGoOnAsTheUninterruptedOnes)
{
  const Parabola curve;
  CurveResolution going, resumed;
  going.start(1e-3, floor);
  for (int k = 0; k < 3; ++k) going.reached(k + 1, k, false, 3.0 * k, curve(3.0 * k));
  StepControllerState state;
  going.save(state);
  resumed.start(1e-3, floor);
  resumed.restore(state);
  going.reached(4, 3, false, 10.0, curve(10.0));
  resumed.reached(4, 3, false, 10.0, curve(10.0));
  EXPECT_DOUBLE_EQ(resumed.limit(100.0), going.limit(100.0));
}

// Stepping over the parabola's top with the increments the bound allows (capped at 20, growing by 1.5): the largest
// sample lies within tol R_max of the true peak, where the cap alone misses it by more.
TEST(CurveResolution, SampledPeakWithinTheTolerance)
{
  const Parabola curve;
  const double tolerance = 1e-3, cap = 20.0;
  auto sampled_peak = [&](double tol) {
    CurveResolution resolution;
    resolution.start(tol, floor);
    double x = 1.0, increment = 1.0, best = -1e300;
    for (int step = 1; x < 90.0; ++step) {
      resolution.reached(step, step - 1, false, x, curve(x));
      best = std::max(best, curve(x));
      increment = resolution.limit(std::min(1.5 * increment, cap));
      x += increment;
    }
    return best;
  };
  const double largest = std::abs(curve(90.0));   // the stage's largest |R| by the end
  EXPECT_LE(curve.top - sampled_peak(tolerance), tolerance * largest);
  EXPECT_GT(curve.top - sampled_peak(0.0), tolerance * largest);   // the test can tell
}

}  // namespace
