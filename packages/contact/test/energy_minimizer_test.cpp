// The energy minimizer alone on a small nonconvex model with known stable states: the adhering bar of
// adhering_bar.hpp at a fixed lift w. Its equilibria are uniform states (gap g, stretch s) with
// phi'(g) = mu (s - 1/s) and w = (g - g_eq) + H (s - 1); the finite element model holds them exactly (a uniform
// stretch, a uniform gap), so the minimizer must end on the analytic stable state to Newton's tolerance:
//   - past the pull-off fold, from a uniform state on the falling side of the attraction (its tangent indefinite:
//     the minimizer has to shift it), on the only stable state left, the far one in the Lennard-Jones tail;
//   - below the fold, from the bar glued at rest with its top lifted, on the near state (the one whose basin it is);
//   - a descent stopped by its watch and resumed from what the watch saw ends where the uninterrupted one does.
// Both methods (shifted Newton, trust region) end on the same states; auto descends as the one it chooses.
#include "adhering_bar.hpp"
#include "discretization/system_fields.hpp"
#include "solvers/energy_minimizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace spatula;

namespace {

using discretization::Master;

struct Minimization : test::AdheringBar {
  solvers::EnergyMinimizer minimizer{*model, *newton, nullptr, false};
  double area = side * side;

  explicit Minimization(solvers::MinimizerParameters::Method method = {}, int trust_region_from = 100000)
  {
    system->set_control({{true, true, true}});
    solvers::MinimizerParameters parameters;
    parameters.method = method;
    parameters.trust_region_from = trust_region_from;
    minimizer.set_parameters(parameters);
  }

  // The bar's uniform state of gap g and stretch s at the lift w (nodes at height z move by
  // (g - g_eq) + z (s - 1), the rigid top with the lift master).
  Teuchos::RCP<discretization::Vector> uniform_state(double w, double g, double s) const
  {
    auto x = system->create_vector();
    std::vector<double> u(3 * mesh.node_count(), 0.0);
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      u[3 * n + 2] = (g - bar.law.equilibrium_gap()) + mesh.coordinates[n][2] * (s - 1.0);
    discretization::set_displacements(*system, *x, u);
    system->set_master(*x, Master::lift, w);
    return x;
  }
  double pull(const discretization::Vector& x) const { return system->evaluate(x, nullptr, false).master_residual[1]; }
  // The analytic equilibrium's gap at the lift w within [a, b] (the balance changes sign there).
  double equilibrium_gap(double w, double a, double b) const
  {
    return test::bisect(
        [&](double g) {
          const double s = 1.0 + (w - (g - bar.law.equilibrium_gap())) / bar.height;
          return bar.derivative(g) - bar.mu * (s - 1.0 / s);
        },
        a, b);
  }
  double fold_lift() const
  {
    const double g = test::bisect([&](double gap) { return bar.second_variation(gap); },
                                  bar.law.strongest_attraction_gap(), bar.law.r0 * std::pow(2.0, -1.0 / 6.0));
    return bar.lift(g, bar.stretch_at(g));
  }
  // Half a nanometre past the fold, the uniform state at the attraction's steepest fall (phi'' most negative).
  double past_fold_lift() const { return fold_lift() + 0.5; }
  double steepest_fall_gap() const { return bar.law.r0 * std::pow(2.0, -1.0 / 6.0); }
  double steepest_fall_stretch() const
  {
    return 1.0 + (past_fold_lift() - (steepest_fall_gap() - bar.law.equilibrium_gap())) / bar.height;
  }
  Teuchos::RCP<discretization::Vector> past_the_fold() const
  {
    return uniform_state(past_fold_lift(), steepest_fall_gap(), steepest_fall_stretch());
  }
};

using Method = solvers::MinimizerParameters::Method;
class EachMethod : public ::testing::TestWithParam<Method> {};

TEST_P(EachMethod, PastTheFoldFromAnIndefiniteStartReachesTheFarStableState)
{
  Minimization m(GetParam());
  const auto& law = m.bar.law;
  const double w = m.past_fold_lift(), g0 = m.steepest_fall_gap(), s0 = m.steepest_fall_stretch();
  double phi, dphi, d2phi;
  law.exact(g0, phi, dphi, d2phi);
  ASSERT_LT(d2phi + m.bar.mu * (1.0 + 1.0 / (s0 * s0)) / m.bar.height, 0.0) << "the start is not on the unstable part";
  auto x = m.past_the_fold();
  const double start_energy = m.system->evaluate(*x, nullptr, false).energy();

  const auto result = m.minimizer.minimize(*x);
  ASSERT_TRUE(result.found) << result.failure;
  if (GetParam() == Method::shifted_newton) {   // (the trust region follows the negative curvature instead)
    EXPECT_GE(result.indefinite_tangents, 1) << "the start's tangent was not seen to be indefinite";
  }
  const double g_far = m.equilibrium_gap(w, g0, w + law.equilibrium_gap() - 1e-9);
  const double s_far = 1.0 + (w - (g_far - law.equilibrium_gap())) / m.bar.height;
  EXPECT_NEAR(m.pull(*x), m.area * m.bar.derivative(g_far), 1e-4 * m.area * m.bar.derivative(g_far));
  EXPECT_NEAR(m.system->master(*x, Master::lift), w, 1e-12);   // the load held
  // Pi at the minimum is the analytic potential A (H W(s) + phi(g)) of the far state, below the start's.
  const double energy = m.system->evaluate(*x, nullptr, false).energy();
  EXPECT_NEAR(energy, m.area * m.bar.potential(g_far, s_far), 1e-6 * std::abs(start_energy));
  EXPECT_LT(energy, start_energy);
}

TEST_P(EachMethod, BelowTheFoldFromTheGluedBarReachesTheNearStableState)
{
  Minimization m(GetParam());
  const auto& law = m.bar.law;
  const double w = 1.5;   // nm, below the fold at about 2.6 nm
  ASSERT_LT(w, m.fold_lift());
  auto x = m.uniform_state(w, law.equilibrium_gap(), 1.0);   // at rest, only the rigid top lifted
  const auto result = m.minimizer.minimize(*x);
  ASSERT_TRUE(result.found) << result.failure;
  const double g_near = m.equilibrium_gap(w, law.equilibrium_gap(), law.strongest_attraction_gap());
  EXPECT_NEAR(m.pull(*x), m.area * m.bar.derivative(g_near), 1e-5 * m.area * m.bar.derivative(g_near));
}

INSTANTIATE_TEST_SUITE_P(EnergyMinimizer, EachMethod, ::testing::Values(Method::shifted_newton, Method::trust_region),
                         [](const ::testing::TestParamInfo<Method>& info) {
                           return info.param == Method::shifted_newton ? "ShiftedNewton" : "TrustRegion";
                         });

// method = auto takes the trust region for a system of at least 'trust region from' unknowns and shifted Newton below:
// from the indefinite start past the fold it then descends exactly as the method it chose.
TEST(EnergyMinimizer, AutoChoosesTheMethodBySystemSize)
{
  const auto unknowns = static_cast<int>(Minimization().system->owned_map()->getGlobalNumElements());
  for (const bool large : {false, true}) {
    Minimization automatic(Method::automatic, large ? unknowns : unknowns + 1);
    Minimization named(large ? Method::trust_region : Method::shifted_newton);
    EXPECT_EQ(automatic.minimizer.uses_trust_region(), large);
    auto x = automatic.past_the_fold(), y = named.past_the_fold();
    const auto chosen = automatic.minimizer.minimize(*x), reference = named.minimizer.minimize(*y);
    ASSERT_TRUE(chosen.found && reference.found) << chosen.failure << reference.failure;
    EXPECT_EQ(chosen.iterations, reference.iterations) << (large ? "trust region" : "shifted newton");
    EXPECT_EQ(chosen.indefinite_tangents, reference.indefinite_tangents);
    x->update(-1.0, *y, 1.0);
    EXPECT_EQ(x->normInf(), 0.0);
  }
}

TEST(EnergyMinimizer, ADescentStoppedByItsWatchGoesOnFromWhatTheWatchSaw)
{
  Minimization whole, stopped;
  const auto& law = whole.bar.law;
  const double w = whole.fold_lift() + 0.5;
  auto x = whole.uniform_state(w, law.equilibrium_gap(), 1.0);
  const auto result = whole.minimizer.minimize(*x);
  ASSERT_TRUE(result.found) << result.failure;
  ASSERT_GT(result.iterations, 4);

  auto y = stopped.uniform_state(w, law.equilibrium_gap(), 1.0);
  auto seen = stopped.system->create_vector();
  solvers::DescentProgress progress;
  struct Stop {};
  try {
    stopped.minimizer.minimize(*y, nullptr, [&](const discretization::Vector& state, const solvers::DescentProgress& p) {
      seen->assign(state);
      progress = p;
      if (p.iterations == 3) throw Stop{};
    });
    FAIL() << "the watch did not stop the descent";
  } catch (const Stop&) {
  }
  EXPECT_EQ(progress.iterations, 3);
  const auto resumed = stopped.minimizer.minimize(*seen, &progress);
  ASSERT_TRUE(resumed.found) << resumed.failure;
  EXPECT_EQ(resumed.iterations, result.iterations);
  EXPECT_EQ(stopped.pull(*seen), whole.pull(*x));
}

}  // namespace
