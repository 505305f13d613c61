// Newton on the coarse spatula (no adhesion, the end face rotated by 0.01 rad with the lift free): every linear
// solver and forcing term reaches the same equilibrium, whose reactions balance (zero net lift force, a positive
// restoring moment), and a fresh factorization per iteration converges quadratically.
#include "solvers/newton.hpp"
#include "solvers/node_blocks.hpp"
#include "same_fields.hpp"
#include "mesh/spatula_mesher.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <cmath>
#include <gtest/gtest.h>

namespace {

using namespace spatula;

struct Equilibrium {
  Teuchos::RCP<discretization::Vector> x;
  solvers::NewtonResult result;
  double moment = 0.0, lift_force = 0.0;
  solvers::MultigridStatistics multigrid;
  int factorizations = 0;
};

Equilibrium rotate(const solvers::LinearSolverParameters& linear_parameters, solvers::NewtonParameters newton_parameters)
{
  const geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  const auto mesh = mesh::mesh_spatula(shape, mesh::MeshParameters{});
  auto comm = Teuchos::DefaultComm<int>::getComm();
  const auto partition = mesh::partition_mesh(mesh, comm->getSize());
  const auto p1 = shape.point(1);
  auto system = Teuchos::rcp(new discretization::DiscreteSystem(
      mesh, partition, discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, true), {}, comm));
  solvers::LinearSolverFactory linear(linear_parameters,
                                      std::make_shared<const solvers::NodeBlocks>(solvers::node_blocks(*system)));
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  newton_parameters.relative_tolerance = 1e-12;
  newton_parameters.update_tolerance = 1e-10;
  solvers::NewtonSolver newton(model, newton_parameters, linear);
  system->set_control({{true, false, true}});   // rotation prescribed, lift free, slide held
  Equilibrium equilibrium;
  equilibrium.x = system->create_vector();
  system->set_master(*equilibrium.x, discretization::Master::rotation, 0.01);
  equilibrium.result = newton.solve(*equilibrium.x, nullptr);
  const auto evaluation = system->evaluate(*equilibrium.x, nullptr, false);
  equilibrium.moment = evaluation.master_residual[0];
  equilibrium.lift_force = evaluation.master_residual[1];
  equilibrium.multigrid = linear.multigrid_statistics();
  equilibrium.factorizations = linear.mumps_statistics().factorizations;
  return equilibrium;
}

double relative_difference(const discretization::Vector& a, const discretization::Vector& b)
{
  discretization::Vector difference(a, Teuchos::Copy);
  difference.update(-1.0, b, 1.0);
  return difference.normInf() / a.normInf();
}

}  // namespace

TEST(Newton, EveryLinearSolverAndForcingTermReachesTheSameEquilibrium)
{
  solvers::LinearSolverParameters fresh;   // a factorization per iteration, every solve to 1e-10
  fresh.refactor = solvers::RefactorRule::lag;
  fresh.lag = 0;
  solvers::NewtonParameters exact;
  exact.inexact = false;
  const auto reference = rotate(fresh, exact);
  ASSERT_TRUE(reference.result.converged) << reference.result.failure;
  EXPECT_GT(reference.moment, 0.0);   // the shaft resists the rotation
  EXPECT_NEAR(reference.lift_force, 0.0, 1e-8 * reference.moment);   // the lift is free

  // Quadratic convergence with exact tangents and exact solves: |f_k+1| <= C |f_k|^2 in the last iterations.
  const auto& rows = reference.result.iterations;
  ASSERT_GE(rows.size(), 3u);
  const double f0 = reference.result.initial_residual_norm;
  const double a = rows[rows.size() - 3].residual_norm / f0, b = rows[rows.size() - 2].residual_norm / f0;
  EXPECT_LT(b, 10.0 * a * a) << "|f| / |f0|: " << a << " then " << b;

  const auto inexact = rotate(solvers::LinearSolverParameters{}, solvers::NewtonParameters{});   // the defaults
  ASSERT_TRUE(inexact.result.converged) << inexact.result.failure;
  EXPECT_LT(relative_difference(*reference.x, *inexact.x), 1e-8);

  solvers::LinearSolverParameters ilu;
  ilu.type = solvers::LinearSolverType::gmres_ilu;
  const auto iterative = rotate(ilu, solvers::NewtonParameters{});
  ASSERT_TRUE(iterative.result.converged) << iterative.result.failure;
  EXPECT_LT(relative_difference(*reference.x, *iterative.x), 1e-8);
}

// Algebraic multigrid (MueLu smoothed aggregation with the rigid-body modes) inside GMRES gives Newton the same
// directions as MUMPS when both solve each system to 1e-12: the same residual after every iteration, the same
// equilibrium. And where its GMRES stalls, MUMPS takes over and Newton still reaches that equilibrium.
TEST(Newton, AlgebraicMultigridGivesTheIteratesOfTheDirectSolver)
{
  solvers::LinearSolverParameters direct;
  direct.refactor = solvers::RefactorRule::lag;
  direct.lag = 0;
  direct.tolerance = 1e-12;
  solvers::NewtonParameters exact;
  exact.inexact = false;
  const auto reference = rotate(direct, exact);
  ASSERT_TRUE(reference.result.converged) << reference.result.failure;

  solvers::LinearSolverParameters algebraic;
  algebraic.type = solvers::LinearSolverType::gmres_amg;
  algebraic.tolerance = 1e-12;
  const auto multigrid = rotate(algebraic, exact);
  ASSERT_TRUE(multigrid.result.converged) << multigrid.result.failure;
  EXPECT_EQ(multigrid.multigrid.setups, 1);   // one hierarchy, reused by the later tangents
  EXPECT_EQ(multigrid.multigrid.reuses + 1, static_cast<int>(multigrid.result.iterations.size()));
  EXPECT_FALSE(multigrid.multigrid.fell_back);
  EXPECT_EQ(multigrid.factorizations, 0);
  ASSERT_EQ(multigrid.result.iterations.size(), reference.result.iterations.size());
  const double f0 = reference.result.initial_residual_norm;
  for (std::size_t k = 0; k < reference.result.iterations.size(); ++k) {
    const double a = reference.result.iterations[k].residual_norm, b = multigrid.result.iterations[k].residual_norm;
    EXPECT_LT(std::abs(a - b), 1e-8 * f0) << "iteration " << k + 1 << ": |f| " << a << " against " << b;
  }
  EXPECT_LT(relative_difference(*reference.x, *multigrid.x), 1e-8);

  algebraic.maximum_iterations = 2;   // too few for any solve: the first stalls, MUMPS serves the rest
  algebraic.refactor = solvers::RefactorRule::lag;   // with fresh factors (one GMRES iteration each)
  algebraic.lag = 0;
  const auto rescued = rotate(algebraic, solvers::NewtonParameters{});
  ASSERT_TRUE(rescued.result.converged) << rescued.result.failure;
  EXPECT_TRUE(rescued.multigrid.fell_back);
  EXPECT_EQ(rescued.multigrid.setups, 1);
  EXPECT_GE(rescued.factorizations, 1);
  EXPECT_LT(relative_difference(*reference.x, *rescued.x), 1e-8);
}

// One source for every default: the valid parameter list declares the typed structs' own defaults, so a list with
// nothing set reads back as a default-constructed struct, field by field.
TEST(Parameters, AnEmptyListReadsBackAsTheTypedDefaults)
{
  Teuchos::ParameterList newton_list, linear_list;
  solvers::NewtonParameters::declare(newton_list);
  solvers::LinearSolverParameters::declare(linear_list);
  using Newton = solvers::NewtonParameters;
  expect_same_fields(Newton::from(newton_list), Newton{}, &Newton::relative_tolerance, &Newton::absolute_tolerance,
                     &Newton::update_tolerance, &Newton::maximum_iterations, &Newton::line_search, &Newton::scaled_norms,
                     &Newton::inexact, &Newton::non_contracting_iterations, &Newton::give_up_only_after_failure,
                     &Newton::contraction, &Newton::short_steps, &Newton::short_step, &Newton::converging_extension);
  using Elimination = solvers::FrontEliminationParameters;
  expect_same_fields(Newton::from(newton_list).elimination, Elimination{}, &Elimination::use, &Elimination::node_share,
                     &Elimination::maximum_nodes, &Elimination::iterations, &Elimination::reduction);
  using Linear = solvers::LinearSolverParameters;
  const auto linear = Linear::from(linear_list);
  expect_same_fields(linear, Linear{}, &Linear::type, &Linear::tolerance, &Linear::maximum_iterations,
                     &Linear::fill_level, &Linear::lag, &Linear::lag_applications, &Linear::refactor);
  using Mumps = solvers::MumpsParameters;
  expect_same_fields(linear.mumps, Linear{}.mumps, &Mumps::symmetric, &Mumps::memory_relaxation, &Mumps::verbose,
                     &Mumps::keep_workspace, &Mumps::ordering, &Mumps::low_rank_tolerance, &Mumps::low_rank_from,
                     &Mumps::single_precision);
  EXPECT_EQ(linear_list.get<int>("lag"), 4);   // the documented default of the lag rule
}
