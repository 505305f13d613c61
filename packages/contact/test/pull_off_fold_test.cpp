// The step controller finds a fold where it is: a soft bar (Neo-Hookean, nu = 0) whose bottom face adheres to a
// flat substrate by the Lennard-Jones law is pulled off by lifting its rigid top face. With nu = 0 the bar stays in
// uniaxial stretch s with lateral stretch 1 (P = mu (s - 1/s)) and the gap g is the same everywhere, so the
// equilibria at a lift w solve
//
//   phi'(g) = mu (s - 1/s),    w = (g - g_eq) + H (s - 1),
//
// and the path has its pull-off fold where the second variation vanishes on the rising side of the attraction,
// phi''(g) + mu (1 + 1/s^2) / H = 0 (a softer bar snaps off earlier than the law's strongest attraction). Past the
// fold the bar snaps to the far equilibrium at the same lift, releasing the difference of the total potential
// H W(s) + phi(g), W(s) = mu/2 (s^2 - 1) - mu ln s, per unit area. The load path must stop within a few minimum
// increments before the analytic fold, never past it, and its jump must release that energy (the fold lies at
// about 2.6 nm, the snap releases about 2.13 nN nm; the descent's far state lies in the flat Lennard-Jones tail).
#include "adhering_bar.hpp"
#include "analysis/instability_policy.hpp"
#include "analysis/load_stepping.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <functional>

using namespace spatula;

using test::bisect;

// The bar of the header on a 1 x 1 x 8 box mesh, its model and a load path with jumps past folds and the app's
// step balance check (1e-4 of the contact energy A w_adh): the energy line search can carry a Newton attempt just
// past the fold down to the far branch, which the check catches and cuts back.
struct BarPath : test::AdheringBar {
  std::unique_ptr<analysis::LoadPath> path;
  analysis::StepParameters steps;

  BarPath(analysis::JumpParameters jump_parameters, const solvers::NewtonParameters& newton_parameters = {})
      : AdheringBar(newton_parameters)
  {
    path = std::make_unique<analysis::LoadPath>(*model, *newton, nullptr, false);
    path->set_instability_policy(analysis::InstabilityPolicies::instance().make("jump", {}));
    jump_parameters.step_balance_tolerance = 1e-4 * side * side * work_of_adhesion;
    path->set_jump_parameters(jump_parameters);
    steps.initial = 0.2;
    steps.maximum = 0.5;
    steps.minimum = 1e-3;
  }

  std::optional<analysis::Failure> lift_to(double w)
  {
    return path->advance(discretization::Master::lift, w,
                         discretization::MasterControl::moving(discretization::Master::lift), steps, 1.0, {});
  }
};

// The lift to the fold and past it; the jump's energy descent with a fresh factorization every iteration, with
// factors kept for up to 'reused factors' further iterations, or kept by the cost rule; with early descents after
// failed attempts, refused at the fold (the snap releases more than the step balance tolerance).
static void expect_stop_at_the_fold_and_the_jumps_release(const analysis::JumpParameters& jump_parameters)
{
  BarPath bar_path(jump_parameters);
  const auto& bar = bar_path.bar;
  const auto& steps = bar_path.steps;
  const double side = BarPath::side;

  // The analytic fold: between the strongest attraction (phi'' = 0) and the steepest fall of the attraction.
  const double strongest = bar.law.strongest_attraction_gap();
  const double steepest = bar.law.r0 * std::pow(2.0, -1.0 / 6.0);   // phi''' = 0
  const double g_fold = bisect([&](double g) { return bar.second_variation(g); }, strongest, steepest);
  const double s_fold = bar.stretch_at(g_fold), w_fold = bar.lift(g_fold, s_fold);
  const double area = side * side, pull_fold = area * bar.derivative(g_fold);
  // The far equilibrium at the same lift, and the energy the snap releases.
  const auto far_balance = [&](double g) {
    const double s = 1.0 + (w_fold - (g - bar.law.equilibrium_gap())) / bar.height;
    return bar.derivative(g) - bar.mu * (s - 1.0 / s);
  };
  const double g_far = bisect(far_balance, 1.0, w_fold + bar.law.equilibrium_gap() - 1e-9);
  const double s_far = 1.0 + (w_fold - (g_far - bar.law.equilibrium_gap())) / bar.height;
  const double released = area * (bar.potential(g_fold, s_fold) - bar.potential(g_far, s_far));
  ASSERT_GT(w_fold, 2.0);   // the numbers the header describes: about 2.6 nm, 1.98 nN, 2.13 nN nm
  ASSERT_LT(w_fold, 3.0);

  const auto failure = bar_path.lift_to(w_fold + 1.0);
  ASSERT_FALSE(failure.has_value()) << failure->reason;
  const auto& points = bar_path.path->points();
  std::size_t jump = 0;
  for (std::size_t k = 1; k < points.size(); ++k)
    if (points[k].after_jump) {
      jump = k;
      break;
    }
  ASSERT_GT(jump, 0u) << "no jump on the path";
  const auto& before = points[jump - 1];
  const auto& after = points[jump];
  EXPECT_LE(before.lift, w_fold + 1e-6) << "a converged state past the fold";
  EXPECT_GT(before.lift, w_fold - 5.0 * steps.minimum) << "stopped short of the fold at " << w_fold;
  EXPECT_NEAR(before.force, pull_fold, 1e-3 * pull_fold);
  // The jump is made at the first load it could not reach: within the last increment tried, at least the minimum.
  EXPECT_GE(after.lift - before.lift, steps.minimum * (1.0 - 1e-9));
  EXPECT_LT(after.lift - before.lift, 2.0 * steps.minimum);
  EXPECT_NEAR(after.released, released, 0.01 * released);
  EXPECT_NEAR(after.force, area * bar.derivative(g_far), 0.02 * area * bar.derivative(g_far));
  for (std::size_t k = jump + 1; k < points.size(); ++k) EXPECT_FALSE(points[k].after_jump);
  // Early descents at the fold are tried and refused (the snap releases far more than the tolerance).
  const auto& early = bar_path.path->early_descents();
  if (jump_parameters.descend_after_failures > 0) {
    EXPECT_GE(early.tried, 1);
  }
  EXPECT_EQ(early.taken, 0);
  // Kept factors serve iterations without a factorization: the cost rule keeps fresh factors for one iteration at
  // least, the count rule for `reused_factors`; without either every iteration factors afresh and solves at most once
  // with its factors (an indefinite one not at all). (Counted, not inferred from solves against factorizations: which
  // iterations the cost rule keeps depends on the clocks, and with them how many indefinite tries there are.)
  const auto* descents = bar_path.path->descent_statistics();
  ASSERT_NE(descents, nullptr);
  if (jump_parameters.refactor == analysis::JumpParameters::Refactor::cost || jump_parameters.reused_factors > 0) {
    EXPECT_GT(descents->reused, 0) << "no descent iteration was served by kept factors";
  } else {
    EXPECT_EQ(descents->reused, 0);
    EXPECT_LE(descents->solves, descents->factorizations);
  }
}

analysis::JumpParameters jump_with(int reused_factors, analysis::JumpParameters::Refactor refactor,
                                   int descend_after_failures = 0)
{
  analysis::JumpParameters parameters;
  parameters.reused_factors = reused_factors;
  parameters.refactor = refactor;
  parameters.descend_after_failures = descend_after_failures;
  return parameters;
}

constexpr auto count = analysis::JumpParameters::Refactor::count;

TEST(PullOffFold, StepControllerStopsAtTheAnalyticFoldAndTheJumpReleasesItsEnergy)
{
  expect_stop_at_the_fold_and_the_jumps_release(jump_with(0, count));
}

TEST(PullOffFold, TheJumpWithReusedDescentFactorsReleasesTheSameEnergy)
{
  expect_stop_at_the_fold_and_the_jumps_release(jump_with(8, count));
}

TEST(PullOffFold, TheJumpWithCostRuledDescentFactorsReleasesTheSameEnergy)
{
  expect_stop_at_the_fold_and_the_jumps_release(jump_with(0, analysis::JumpParameters::Refactor::cost));
}

TEST(PullOffFold, AnEarlyDescentAtTheFoldIsRefusedAndTheFoldStillFound)
{
  expect_stop_at_the_fold_and_the_jumps_release(jump_with(0, count, 1));
}

// Newton allowed a single iteration fails the first steps on the smooth rising branch (no predictor yet); with
// early descents after one failure those steps are the energy descent's at the load Newton failed, ordinary steps
// (no energy released), instead of a bisection down to the smallest increment and a jump there; every state is the
// analytic equilibrium at its lift.
TEST(PullOffFold, EarlyDescentsTakeTheStepsNewtonFailsOnASmoothBranch)
{
  solvers::NewtonParameters one_iteration;
  one_iteration.maximum_iterations = 1;
  one_iteration.non_contracting_iterations = 0;
  BarPath bar_path(jump_with(0, count, 1), one_iteration);
  const double target = 1.5;   // nm, below the fold at about 2.6 nm
  const auto failure = bar_path.lift_to(target);
  ASSERT_FALSE(failure.has_value()) << failure->reason;
  const auto& points = bar_path.path->points();
  ASSERT_GE(points.size(), 4u);
  EXPECT_NEAR(points[1].lift, bar_path.steps.initial, 1e-12);   // the first step, at the initial increment
  EXPECT_NEAR(points.back().lift, target, 1e-12);
  const auto& bar = bar_path.bar;
  const double area = BarPath::side * BarPath::side;
  const double g_fold = bisect([&](double g) { return bar.second_variation(g); }, bar.law.strongest_attraction_gap(),
                               bar.law.r0 * std::pow(2.0, -1.0 / 6.0));
  for (std::size_t k = 1; k < points.size(); ++k) {
    EXPECT_FALSE(points[k].after_jump);
    // The analytic pull at this lift: the gap g with w = (g - g_eq) + H (s(g) - 1), by bisection.
    const double w = points[k].lift;
    const double g = bisect([&](double gap) { return bar.lift(gap, bar.stretch_at(gap)) - w; },
                            bar.law.equilibrium_gap(), g_fold);
    EXPECT_NEAR(points[k].force, area * bar.derivative(g), 1e-5 * area * std::abs(bar.derivative(g)))
        << "at the lift " << w;
  }
  EXPECT_GE(bar_path.path->early_descents().taken, 1);
}

// The load path takes its corrector through solvers::EquilibriumSolver: a solver put in Newton's place (here one that
// counts its calls and hands them on) is used for every step, the jump's confirmation included, and the path is the
// one Newton alone follows.
TEST(PullOffFold, TheLoadPathUsesTheEquilibriumSolverItIsGiven)
{
  class CountingSolver : public solvers::EquilibriumSolver {
  public:
    explicit CountingSolver(const solvers::EquilibriumSolver& inner) : inner_(inner) {}
    solvers::NewtonResult solve(discretization::Vector& x, std::ostream* table, bool after_failure) const override
    {
      ++calls;
      return inner_.solve(x, table, after_failure);
    }
    const solvers::LinearSolverFactory& linear_solver() const override { return inner_.linear_solver(); }
    mutable int calls = 0;

  private:
    const solvers::EquilibriumSolver& inner_;
  };
  analysis::JumpParameters jump;
  BarPath alone(jump), counted(jump);
  CountingSolver counting(*counted.newton);
  counted.path = std::make_unique<analysis::LoadPath>(*counted.model, counting, nullptr, false);
  counted.path->set_instability_policy(analysis::InstabilityPolicies::instance().make("jump", {}));
  jump.step_balance_tolerance = 1e-4 * BarPath::side * BarPath::side * alone.bar.law.work_of_adhesion();
  counted.path->set_jump_parameters(jump);
  const double target = 4.0;   // past the fold (about 2.6 nm): a jump on the way
  ASSERT_FALSE(alone.lift_to(target).has_value());
  ASSERT_FALSE(counted.lift_to(target).has_value());
  const auto &a = alone.path->points(), &b = counted.path->points();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].lift, b[k].lift);
    EXPECT_EQ(a[k].force, b[k].force);
    EXPECT_EQ(a[k].after_jump, b[k].after_jump);
  }
  EXPECT_TRUE(std::any_of(b.begin(), b.end(), [](const analysis::LoadPoint& p) { return p.after_jump; }));
  EXPECT_GE(counting.calls, static_cast<int>(b.size()) - 1);   // every converged step came through it
}

// The instability policies are a registry: a policy added by name is the one the path asks at the fold, without an
// edit to the load path. Here one that records where it was asked and then stops the path there: the lift ends at
// the analytic fold (about 2.6 nm) with a failure, and the policy saw that load.
TEST(PullOffFold, AnInstabilityPolicyAddedByNameIsAskedAtTheFold)
{
  struct Recorded {
    int folds = 0;
    double unreached = 0.0;
  };
  auto recorded = std::make_shared<Recorded>();
  class RecordAndStop : public analysis::InstabilityPolicy {
  public:
    explicit RecordAndStop(std::shared_ptr<Recorded> recorded) : recorded_(std::move(recorded)) {}
    bool jumps() const override { return false; }
    bool counts_snaps_as_jumps() const override { return false; }
    std::optional<std::variant<double, analysis::Failure>> pass(analysis::LoadPath&, const analysis::LoadPath::Fold& fold,
                                                               const analysis::LoadPath::Callback&) const override
    {
      ++recorded_->folds;
      recorded_->unreached = fold.unreached / fold.unit;
      return std::nullopt;   // stop with Newton's failure
    }

  private:
    std::shared_ptr<Recorded> recorded_;
  };
  auto& policies = analysis::InstabilityPolicies::instance();
  policies.add("record and stop", [recorded](const analysis::ArcLengthParameters&) {
    return std::make_shared<const RecordAndStop>(recorded);
  });
  const auto names = policies.names();
  EXPECT_NE(std::find(names.begin(), names.end(), "record and stop"), names.end());
  BarPath bar_path(analysis::JumpParameters{});
  bar_path.path->set_instability_policy(policies.make("record and stop", {}));
  const auto failure = bar_path.lift_to(4.0);
  ASSERT_TRUE(failure.has_value());
  EXPECT_EQ(recorded->folds, 1);
  EXPECT_NEAR(failure->load, recorded->unreached, 1e-12);
  EXPECT_GT(recorded->unreached, 2.0);   // at the fold, not before it
  EXPECT_LT(recorded->unreached, 3.0);
}

// Under a dead load on the lift master (advance_force) the bar's states are the analytic near branch at each force
// F: phi'(g) = F / A = mu (s - 1/s), lift w = (g - g_eq) + H (s - 1). The largest force it carries is the law's
// strongest attraction A phi'(g*) (phi''(g*) = 0, beyond the displacement-controlled fold's force): asked for more,
// the path stops there with a failure marked largest_force, its last state within a few minimum increments of it.
TEST(PullOffFold, UnderADeadLoadTheBarFollowsItsAnalyticBranchUpToTheLargestForce)
{
  BarPath bar_path(analysis::JumpParameters{});
  const auto& bar = bar_path.bar;
  const double area = BarPath::side * BarPath::side;
  const double g_largest = bar.law.strongest_attraction_gap();
  const double largest = area * bar.derivative(g_largest);
  const auto lift = discretization::Master::lift;
  auto failure = bar_path.path->advance_force(lift, 0.9 * largest, {}, bar_path.steps, 1.0, {});
  ASSERT_FALSE(failure.has_value()) << failure->reason;
  const auto& points = bar_path.path->points();
  ASSERT_GE(points.size(), 4u);
  EXPECT_NEAR(points.back().force, 0.9 * largest, 1e-6 * largest);
  for (std::size_t k = 1; k < points.size(); ++k) {
    const double pull = points[k].force;
    const double g = bisect([&](double gap) { return bar.derivative(gap) - pull / area; }, bar.law.equilibrium_gap(),
                            g_largest);
    EXPECT_NEAR(points[k].lift, bar.lift(g, bar.stretch_at(g)), 1e-5) << "at the force " << pull;
    EXPECT_FALSE(points[k].after_jump);
  }
  failure = bar_path.path->advance_force(lift, 1.2 * largest, {}, bar_path.steps, 1.0, {});
  ASSERT_TRUE(failure.has_value());
  EXPECT_TRUE(failure->largest_force) << failure->reason;
  EXPECT_LE(bar_path.path->last().force, largest * (1.0 + 1e-6));
  EXPECT_GT(bar_path.path->last().force, largest - 5.0 * bar_path.steps.minimum);
  EXPECT_GT(failure->load, bar_path.path->last().force);
}

// A path of two lift stages (to 1 nm, below the fold, then past it) is the single lift's path: the same states where
// both sample the same loads, the same far state after the same snap. (The second stage starts its increments
// afresh, so the loads it samples differ; the fold, the jump's release and the end may not.)
TEST(PullOffFold, TwoLiftStagesFollowTheSinglePath)
{
  BarPath single(analysis::JumpParameters{}), staged(analysis::JumpParameters{});
  const double target = 4.0;   // past the fold at about 2.6 nm
  ASSERT_FALSE(single.lift_to(target).has_value());
  ASSERT_FALSE(staged.lift_to(1.0).has_value());
  ASSERT_FALSE(staged.lift_to(target).has_value());
  const auto &a = single.path->points(), &b = staged.path->points();
  const auto jump_of = [](const std::vector<analysis::LoadPoint>& points) {
    return *std::find_if(points.begin(), points.end(), [](const analysis::LoadPoint& p) { return p.after_jump; });
  };
  const auto ja = jump_of(a), jb = jump_of(b);
  EXPECT_NEAR(jb.released, ja.released, 1e-3 * ja.released);
  EXPECT_NEAR(jb.lift, ja.lift, 2.0 * single.steps.minimum);
  EXPECT_NEAR(b.back().lift, a.back().lift, 1e-12);
  EXPECT_NEAR(b.back().force, a.back().force, 1e-6 * std::abs(a.back().force));
  EXPECT_NEAR(b.back().external_work, a.back().external_work, 1e-3 * std::abs(a.back().external_work));
  int shared = 0;
  for (const auto& p : b) {   // where both sampled the same load, the same state
    for (const auto& q : a) {
      if (std::abs(p.lift - q.lift) < 1e-12 && !p.after_jump && !q.after_jump) {
        ++shared;
        EXPECT_NEAR(p.force, q.force, 1e-6 * std::max(1.0, std::abs(q.force))) << "at the lift " << p.lift;
      }
    }
  }
  EXPECT_GE(shared, 3);
}
