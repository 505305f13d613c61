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
// increments before the analytic fold, never past it, and its jump must release that energy. (Measured when written:
// the last state 0.0011 nm before the fold at 2.5995 nm, 2.1342 against 2.1344 nN nm released; the descent's far
// state lies in the flat Lennard-Jones tail, where it used to run its 500 iterations without confirming.)
#include "contact/adhesion.hpp"
#include "mesh/box_mesh.hpp"
#include "analysis/load_stepping.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace spatula;

namespace {

struct AnalyticBar {
  laws::LennardJones law;
  double mu = 1.0, height = 40.0;

  double derivative(double g) const
  {
    double phi, dphi, d2phi;
    law.exact(g, phi, dphi, d2phi);
    return dphi;
  }
  double energy(double g) const
  {
    double phi, dphi, d2phi;
    law.exact(g, phi, dphi, d2phi);
    return phi;
  }
  double stretch_at(double g) const   // s with mu (s - 1/s) = phi'(g)
  {
    const double p = derivative(g);
    return (p + std::sqrt(p * p + 4.0 * mu * mu)) / (2.0 * mu);
  }
  double lift(double g, double s) const { return (g - law.equilibrium_gap()) + height * (s - 1.0); }
  double potential(double g, double s) const   // per unit area
  {
    return height * (0.5 * mu * (s * s - 1.0) - mu * std::log(s)) + energy(g);
  }
  double second_variation(double g) const
  {
    double phi, dphi, d2phi;
    law.exact(g, phi, dphi, d2phi);
    const double s = stretch_at(g);
    return d2phi + mu * (1.0 + 1.0 / (s * s)) / height;
  }
};

// A root of f in [a, b] (f(a) and f(b) of opposite signs) by bisection.
double bisect(const std::function<double(double)>& f, double a, double b)
{
  const bool rising = f(a) < 0.0;
  for (int k = 0; k < 200; ++k) {
    const double middle = 0.5 * (a + b);
    ((f(middle) < 0.0) == rising ? a : b) = middle;
  }
  return 0.5 * (a + b);
}

}  // namespace

// The lift to the fold and past it; the jump's energy descent with a fresh factorization every iteration or with
// factors kept for up to `reused_factors` further iterations.
static void expect_stop_at_the_fold_and_the_jumps_release(int reused_factors)
{
  const double side = 4.0;
  AnalyticBar bar;
  mesh::BoxParameters box;
  box.lengths = {side, side, bar.height};
  box.elements = {1, 1, 8};
  const auto mesh = mesh::box_mesh(box);
  discretization::Constraints constraints;
  constraints.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
  for (std::int64_t n = 0; n < mesh.node_count(); ++n)
    if (mesh.coordinates[n][2] == bar.height) constraints.rigid_nodes.push_back(n);
  constraints.rigid_centre = {0.5 * side, 0.0, bar.height};

  contact::AdhesionSettings adhesion;
  adhesion.law = "frictionless";
  adhesion.enrichment = discretization::Enrichment::q1c1;
  adhesion.quadrature = 2;
  adhesion.lennard_jones.r_reg = 0.8 * adhesion.lennard_jones.equilibrium_gap();
  adhesion.lennard_jones.r_cut = 10.0;   // exact law below 5 nm, where every state here lies
  adhesion.substrate_height = -adhesion.lennard_jones.equilibrium_gap();
  bar.law = adhesion.lennard_jones;
  discretization::SolidParameters solid;
  solid.young = 2.0 * bar.mu;
  solid.poisson = 0.0;

  auto comm = Teuchos::DefaultComm<int>::getComm();
  const auto partition = mesh::partition_mesh(mesh, comm->getSize());
  auto system = Teuchos::rcp(new discretization::DiscreteSystem(
      mesh, partition, constraints, solid, comm, {adhesion.enrichment, contact::make_contact_model(adhesion)}));
  solvers::LinearSolverFactory linear(solvers::LinearSolverParameters{});
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  solvers::NewtonSolver newton(model, solvers::NewtonParameters{}, linear);
  analysis::LoadPath path(*model, newton, nullptr, false);
  path.set_past_folds(analysis::LoadPath::PastFolds::jump);
  // The app's step balance check (1e-4 of the contact energy A w_adh): the energy line search can carry a Newton
  // attempt just past the fold down to the far branch, which the check catches and cuts back.
  analysis::JumpParameters jump_parameters;
  jump_parameters.step_balance_tolerance = 1e-4 * side * side * adhesion.lennard_jones.work_of_adhesion();
  jump_parameters.reused_factors = reused_factors;
  path.set_jump_parameters(jump_parameters);
  analysis::StepParameters steps;
  steps.initial = 0.2;
  steps.maximum = 0.5;
  steps.minimum = 1e-3;

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

  const auto failure = path.advance(discretization::Master::lift, w_fold + 1.0,
                                    analysis::LoadPath::spatula_control(discretization::Master::lift, false), steps,
                                    1.0, {});
  ASSERT_FALSE(failure.has_value()) << failure->reason;
  const auto& points = path.points();
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
  // Every descent iteration with fresh factors solves once with them (an indefinite one not at all); kept factors
  // serve iterations without a factorization.
  const auto* descents = path.descent_statistics();
  ASSERT_NE(descents, nullptr);
  if (reused_factors == 0)
    EXPECT_LE(descents->solves, descents->factorizations);
  else
    EXPECT_GT(descents->solves, descents->factorizations) << "no descent iteration was served by kept factors";
}

TEST(PullOffFold, StepControllerStopsAtTheAnalyticFoldAndTheJumpReleasesItsEnergy)
{
  expect_stop_at_the_fold_and_the_jumps_release(0);
}

TEST(PullOffFold, TheJumpWithReusedDescentFactorsReleasesTheSameEnergy)
{
  expect_stop_at_the_fold_and_the_jumps_release(8);
}
