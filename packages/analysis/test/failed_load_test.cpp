// The step control's memory of a failed load: a load that fails once is tried again; one that fails twice is
// approached by bisection, tried itself only when the gap cannot be halved, and forgotten once reached.
#include "analysis/load_stepping.hpp"

#include <gtest/gtest.h>

using spatula::analysis::FailedLoad;

namespace {

constexpr double smallest = 0.01, cut = 0.5;

// The memory after `load` failed twice: from then on the steps bisect towards it.
FailedLoad bisecting_towards(double load, double direction = 1.0)
{
  FailedLoad failed(direction, smallest, cut);
  failed.failed(load);
  failed.failed(load);
  return failed;
}

TEST(FailedLoad, OneFailureLimitsNothing)
{
  FailedLoad failed(1.0, smallest, cut);
  EXPECT_DOUBLE_EQ(failed.limit(4.0, 6.0), 4.0);
  failed.failed(10.0);   // from 5 with increment 5; the cut retries 7.5, then 10 from there
  EXPECT_DOUBLE_EQ(failed.limit(2.5, 7.5), 2.5);
}

TEST(FailedLoad, TheSameLoadFailingAgainIsApproachedByBisection)
{
  FailedLoad failed(1.0, smallest, cut);
  failed.failed(10.0);
  failed.failed(10.0);   // again, from 7.5
  EXPECT_DOUBLE_EQ(failed.limit(1.25, 7.5), 1.25);
  EXPECT_DOUBLE_EQ(failed.limit(5.0, 8.75), 0.625);   // a grown increment is held to half the gap
  EXPECT_DOUBLE_EQ(failed.limit(0.1, 8.75), 0.1);     // a smaller one is kept
}

TEST(FailedLoad, ALoadBeyondTheFailedOneCountsAsTheSame)
{
  FailedLoad failed(1.0, smallest, cut);
  failed.failed(10.0);
  failed.failed(11.0);   // a grown increment overshot it: the bracket stays at 10
  EXPECT_DOUBLE_EQ(failed.limit(5.0, 8.0), 1.0);
}

TEST(FailedLoad, ANearerFailureWhileBisectingMovesTheBracket)
{
  auto failed = bisecting_towards(10.0);
  failed.failed(9.0);
  EXPECT_DOUBLE_EQ(failed.limit(5.0, 8.0), 0.5);
}

TEST(FailedLoad, AGapTooSmallToHalveIsTriedWhole)
{
  auto failed = bisecting_towards(10.0);
  EXPECT_NEAR(failed.limit(1.0, 9.985), 0.015, 1e-12);   // half of it would be below 0.01
  EXPECT_NEAR(failed.limit(1.0, 9.98), 0.01, 1e-12);     // half of 0.02 is still allowed
}

TEST(FailedLoad, ReachingTheLoadForgetsIt)
{
  auto failed = bisecting_towards(10.0);
  failed.reached(9.5);
  EXPECT_DOUBLE_EQ(failed.limit(5.0, 9.5), 0.25);
  failed.reached(10.0);   // converged there from near: Newton had only been too far away
  EXPECT_DOUBLE_EQ(failed.limit(5.0, 10.0), 5.0);
  failed.failed(20.0);    // a new failed load starts a new count
  EXPECT_DOUBLE_EQ(failed.limit(5.0, 16.0), 5.0);
}

TEST(FailedLoad, ForgetEndsTheBisection)
{
  auto failed = bisecting_towards(10.0);
  failed.forget();   // jumped past it
  EXPECT_DOUBLE_EQ(failed.limit(5.0, 10.0), 5.0);
}

TEST(FailedLoad, UnloadingBisectsDownwards)
{
  auto failed = bisecting_towards(-10.0, -1.0);
  EXPECT_DOUBLE_EQ(failed.limit(5.0, -5.0), 2.5);
  failed.failed(-12.0);   // beyond, in the sense of travel
  EXPECT_DOUBLE_EQ(failed.limit(5.0, -6.0), 2.0);
  failed.reached(-10.0);
  EXPECT_DOUBLE_EQ(failed.limit(5.0, -10.0), 5.0);
}

}  // namespace
