// The front-limited Newton step (solvers/front_elimination.hpp, use = front-limited step) on the adhering bar of
// adhering_bar.hpp (1 x 1 x 8 elements, one contact face with 2 x 2 quadrature points). Its constraint row
// (DiscreteSystem::contact_gap_limit): a rigid translation of the bar away from the substrate by d carries every
// point from the equilibrium gap g_eq past the law's inflection g_i; the row is the integral of the gap's gradient,
// e_z over the face's area A (its entries sum to A, its product with the translation is A d), and the target is
// A (g_i - g_eq); a limit beyond g_eq + d names no point. Newton with the limited step from the undeformed bar to a
// lift whose equilibrium gap lies past the inflection (between it and the pull-off fold) corrects its steps there and
// reaches the state plain Newton reaches.
#include "adhering_bar.hpp"
#include "discretization/system_fields.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatula;

using test::translated;

TEST(FrontLimitedStep, TheRowOfARigidLiftIsTheGapsGradientOverTheFaceAndItsTargetTheWayToTheInflection)
{
  test::AdheringBar bar;
  bar.system->set_control({{true, true, true}});
  const auto& law = bar.bar.law;
  const double d = 0.3, area = test::AdheringBar::side * test::AdheringBar::side;
  const double g_eq = law.equilibrium_gap(), g_i = law.strongest_attraction_gap();
  ASSERT_GT(g_eq + d, g_i);
  const auto from = translated(bar, 0.0), to = translated(bar, d);
  auto row = bar.system->create_vector();
  const auto limit = bar.system->contact_gap_limit(*from, *to, 0.0, *row);
  EXPECT_EQ(limit.points, 4);
  EXPECT_NEAR(limit.target, area * (g_i - g_eq), 1e-12 * area);
  auto ones = bar.system->create_vector();
  ones->putScalar(1.0);
  bar.system->set_master(*ones, discretization::Master::lift, 0.0);   // (the row has no entry there)
  EXPECT_NEAR(row->dot(*ones), area, 1e-9 * area);
  auto step = bar.system->create_vector();
  step->update(1.0, *to, -1.0, *from, 0.0);
  EXPECT_NEAR(row->dot(*step), area * d, 1e-9 * area);
  // The limit beyond where the step ends: no point, no row.
  const auto none = bar.system->contact_gap_limit(*from, *to, g_eq + d - g_i + 0.01, *row);
  EXPECT_EQ(none.points, 0);
  EXPECT_EQ(row->norm2(), 0.0);
}

TEST(FrontLimitedStep, NewtonWithTheLimitedStepReachesPlainNewtonsStatePastTheInflection)
{
  test::AdheringBar plain;
  const auto& analytic = plain.bar;
  const double g_i = analytic.law.strongest_attraction_gap();
  const double steepest = analytic.law.r0 * std::pow(2.0, -1.0 / 6.0);
  const double g_fold = test::bisect([&](double g) { return analytic.second_variation(g); }, g_i, steepest);
  const double g = 0.5 * (g_i + g_fold);   // an equilibrium past the inflection, before the fold
  const double lift = analytic.lift(g, analytic.stretch_at(g));

  const auto solve = [&](test::AdheringBar& bar, solvers::NewtonResult& result) {
    bar.system->set_control(discretization::MasterControl::moving(discretization::Master::lift));
    auto x = bar.system->create_vector();
    bar.system->set_master(*x, discretization::Master::lift, lift);
    result = bar.newton->solve(*x, nullptr);
    return x;
  };
  solvers::NewtonResult plain_result, limited_result;
  const auto plain_state = solve(plain, plain_result);
  ASSERT_TRUE(plain_result.converged) << plain_result.failure;

  solvers::NewtonParameters parameters;
  parameters.elimination.use = solvers::EliminationUse::front_limited_step;
  test::AdheringBar limited(parameters);
  const auto limited_state = solve(limited, limited_result);
  ASSERT_TRUE(limited_result.converged) << limited_result.failure;
  EXPECT_GT(limited_result.elimination.limited_steps, 0) << "no step carried the face past the inflection";
  auto difference = limited.system->create_vector();
  difference->update(1.0, *limited_state, -1.0, *plain_state, 0.0);
  EXPECT_LT(difference->normInf(), 1e-6 * plain_state->normInf());
  // ... the analytic equilibrium's gap (every point at one gap; the bottom face's Z displacement is g - g_eq).
  const auto u = discretization::node_displacements(*limited.system, *limited_state);
  for (std::int64_t n = 0; n < limited.mesh.node_count(); ++n) {
    if (limited.mesh.coordinates[n][2] == 0.0) {
      EXPECT_NEAR(u[3 * n + 2], g - analytic.law.equilibrium_gap(), 1e-4);
    }
  }
}
