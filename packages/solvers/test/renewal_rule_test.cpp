// The renewal rule of kept factors, as Newton's linear solver uses it (a tangent's yield is 1, its cost the work of
// its solves) and as the energy minimizer's descent does (an iteration's yield is its decrease of Pi, its cost its
// seconds): the factors serve the next use while the last one yielded at least the cycle's average rate.
#include "solvers/renewal_rule.hpp"

#include <gtest/gtest.h>

namespace {

using namespace spatula;

TEST(RenewalRule, NewtonKeepsTheFactorsWhileTheLastTangentCostsLessThanTheCycleAverage)
{
  solvers::RenewalRule cost;
  EXPECT_FALSE(cost.keep(0.0, 1.0));   // nothing factored yet
  cost.factored(10.0, 0.0);            // a factorization of 10 s, its own tangent's solves took 1 s
  EXPECT_TRUE(cost.keep(1.0, 1.0));    // 1 <= (10 + 1) / 1
  EXPECT_EQ(cost.uses(), 2);
  EXPECT_TRUE(cost.keep(3.0, 1.0));    // 3 <= (11 + 3) / 2 = 7
  EXPECT_TRUE(cost.keep(4.0, 1.0));    // 4 <= 18 / 3 = 6
  EXPECT_FALSE(cost.keep(7.0, 1.0));   // 7 > 25 / 4: one more tangent would raise the average cost per tangent
  // The same solve times after a cheap and a dear factorization: the cheap one is renewed sooner.
  for (double factorization_seconds : {2.0, 10.0}) {
    cost.factored(factorization_seconds, 0.0);
    EXPECT_TRUE(cost.keep(0.5, 1.0));   // a fresh factorization always serves a second tangent
    EXPECT_TRUE(cost.keep(2.0, 1.0));   // 2 <= (F + 2.5) / 2
    EXPECT_EQ(cost.keep(2.5, 1.0), factorization_seconds > 2.0);   // 2.5 against (F + 5) / 3: 2.33 or 5
  }
}

TEST(RenewalRule, NewtonServesMoreTangentsWhenTheFactorizationIsDearer)
{
  // Solves that cost 1 s more with every tangent the factors age: the cycle length grows like the square root of
  // the factorization's cost F (the average (F + k (k + 1) / 2) / k is least at k = sqrt(2 F)); the rule ends the
  // cycle one tangent after the optimum, as it sees a tangent's cost only after paying it.
  const auto cycle = [](double factorization_seconds) {
    solvers::RenewalRule cost;
    cost.factored(factorization_seconds, 0.0);
    int tangents = 1;
    while (cost.keep(tangents, 1.0)) ++tangents;
    return tangents;
  };
  EXPECT_EQ(cycle(2.0), 3);     // optimum 2
  EXPECT_EQ(cycle(18.0), 7);    // optimum 6
  EXPECT_EQ(cycle(200.0), 21);  // optimum 20
}

TEST(RenewalRule, DescentKeepsTheFactorsWhileTheLastIterationYieldsAtLeastTheCycleRate)
{
  solvers::RenewalRule cost;
  cost.factored(10.0, 8.0);          // a fresh iteration: 10 s (factorization included), Pi lowered by 8
  EXPECT_TRUE(cost.keep(1.0, 2.0));  // 2 per s >= 8 / 10
  EXPECT_TRUE(cost.keep(1.0, 1.0));  // 1 per s >= 10 / 11
  EXPECT_FALSE(cost.keep(1.0, 0.5)); // 0.5 per s < 11 / 12
  EXPECT_FALSE(cost.keep(1.0, 0.0)); // no decrease never keeps the factors
  cost.factored(10.0, 8.0);          // a new cycle forgets the old one
  EXPECT_TRUE(cost.keep(1.0, 0.8));  // 0.8 per s >= 0.8 per s
}

TEST(RenewalRule, DescentServesMoreIterationsWhenTheFactorizationIsDearer)
{
  // Kept factors whose yield halves with every iteration they serve, each iteration 1 s. The factors serve their
  // fresh iteration and always one kept iteration (its yield is measured after it), then those the rule keeps: the
  // dearer the factorization, the longer its cycle.
  const auto served = [](double fresh_seconds) {
    solvers::RenewalRule cost;
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
