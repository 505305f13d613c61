// The cost rule of an energy descent's factors: kept factors serve further iterations while each lowers Pi at least
// as fast per second as the factors' cycle has on average.
#include "analysis/load_stepping.hpp"

#include <gtest/gtest.h>

using spatula::analysis::DescentCost;

namespace {

TEST(DescentCost, KeepsTheFactorsWhileTheLastIterationYieldsAtLeastTheCycleRate)
{
  DescentCost cost;
  cost.factored(10.0, 8.0);          // a fresh iteration: 10 s (factorization included), Pi lowered by 8
  EXPECT_TRUE(cost.keep(1.0, 2.0));  // 2 per s >= 8 / 10
  EXPECT_TRUE(cost.keep(1.0, 1.0));  // 1 per s >= 10 / 11
  EXPECT_FALSE(cost.keep(1.0, 0.5)); // 0.5 per s < 11 / 12
  EXPECT_FALSE(cost.keep(1.0, 0.0)); // no decrease never keeps the factors
  cost.factored(10.0, 8.0);          // a new cycle forgets the old one
  EXPECT_TRUE(cost.keep(1.0, 0.8));  // 0.8 per s >= 0.8 per s
}

TEST(DescentCost, ServesMoreIterationsWhenTheFactorizationIsDearer)
{
  // Kept factors whose yield halves with every iteration they serve, each iteration 1 s. The factors serve their
  // fresh iteration and always one kept iteration (its yield is measured after it), then those the rule keeps: the
  // dearer the factorization, the longer its cycle.
  const auto served = [](double fresh_seconds) {
    DescentCost cost;
    cost.factored(fresh_seconds, 1.0);
    int iterations = 2;
    double yield = 0.5;
    while (cost.keep(1.0, yield)) {
      ++iterations;
      yield *= 0.5;
    }
    return iterations;
  };
  EXPECT_EQ(served(1.0), 2);   // as cheap as a kept iteration: 0.5 per s < 1 per s, refactor after the first kept
  EXPECT_EQ(served(4.0), 3);   // 0.5 >= 1 / 4; 0.25 < 1.5 / 5
  EXPECT_EQ(served(40.0), 6);  // 0.0625 >= 1.875 / 43; 0.03125 < 1.9375 / 44
}

}  // namespace
