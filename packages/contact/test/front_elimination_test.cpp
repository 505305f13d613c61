// Nonlinear elimination of the front (solvers/front_elimination.hpp) on an adhering bar: a soft Neo-Hookean bar whose
// bottom face adheres to a flat substrate by the Lennard-Jones law, its rigid top face lifted by 1 nm (below the
// pull-off fold at about 2.6 nm, see pull_off_fold_test.cpp). One bottom node pushed 0.15 nm off its equilibrium
// carries the residual; the relaxation moves that node alone, lowers the energy and brings its residual below the
// rest's; Newton with the relaxation before every direction, or after full steps, reaches the equilibrium Newton
// reaches without it.
#include "contact/adhesion.hpp"
#include "discretization/system_fields.hpp"
#include "mesh/box_mesh.hpp"
#include "solvers/newton.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace spatula;

namespace {

struct AdheringBar {
  static constexpr double side = 4.0, height = 40.0, lift = 1.0;
  mesh::HexMesh mesh;
  Teuchos::RCP<discretization::DiscreteSystem> system;
  std::unique_ptr<solvers::LinearSolverFactory> linear;
  Teuchos::RCP<solvers::SpatulaModel> model;

  AdheringBar()
  {
    mesh::BoxParameters box;
    box.lengths = {side, side, height};
    box.elements = {2, 2, 8};
    mesh = mesh::box_mesh(box);
    discretization::Constraints constraints;
    constraints.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      if (mesh.coordinates[n][2] == height) constraints.rigid_nodes.push_back(n);
    constraints.rigid_centre = {0.5 * side, 0.0, height};
    contact::AdhesionSettings adhesion;
    adhesion.enrichment = discretization::Enrichment::q1c1;
    adhesion.quadrature = 2;
    adhesion.lennard_jones.r_reg = 0.8 * adhesion.lennard_jones.equilibrium_gap();
    adhesion.substrate_height = -adhesion.lennard_jones.equilibrium_gap();
    discretization::SolidParameters solid;
    solid.young = 2.0;
    solid.poisson = 0.0;
    auto comm = Teuchos::DefaultComm<int>::getComm();
    system = Teuchos::rcp(new discretization::DiscreteSystem(mesh, mesh::partition_mesh(mesh, comm->getSize()),
                                                             constraints, solid, comm,
                                                             {adhesion.enrichment, contact::make_contact_model(adhesion)}));
    system->set_control({{true, true, true}});   // the top face lifted, neither rotated nor slid
    solvers::LinearSolverParameters linear_parameters;
    linear_parameters.refactor = solvers::RefactorRule::lag;
    linear = std::make_unique<solvers::LinearSolverFactory>(linear_parameters);
    model = Teuchos::rcp(new solvers::SpatulaModel(system, linear->lows_factory()));
  }

  // Newton from the undeformed bar with the top lifted, to 1e-12 relative.
  solvers::NewtonResult solve(discretization::Vector& x, solvers::EliminationUse use) const
  {
    solvers::NewtonParameters parameters;
    parameters.relative_tolerance = 1e-12;
    parameters.update_tolerance = 1e-10;
    parameters.elimination.use = use;
    solvers::NewtonSolver newton(model, parameters, *linear);
    return newton.solve(x, nullptr);
  }

  Teuchos::RCP<discretization::Vector> lifted() const
  {
    auto x = system->create_vector();
    system->set_master(*x, discretization::Master::lift, lift);
    return x;
  }

  // The equilibrium with one bottom node (the corner at x = 0, y = 0) moved up by `offset`.
  Teuchos::RCP<discretization::Vector> pushed(const discretization::Vector& equilibrium, double offset) const
  {
    auto u = discretization::node_displacements(*system, equilibrium);
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      if (mesh.coordinates[n][0] == 0.0 && mesh.coordinates[n][1] == 0.0 && mesh.coordinates[n][2] == 0.0)
        u[3 * n + 2] += offset;
    auto x = Teuchos::rcp(new discretization::Vector(equilibrium, Teuchos::Copy));
    discretization::set_displacements(*system, *x, u);
    return x;
  }
};

double relative_difference(const discretization::Vector& a, const discretization::Vector& b)
{
  discretization::Vector difference(a, Teuchos::Copy);
  difference.update(-1.0, b, 1.0);
  return difference.normInf() / a.normInf();
}

}  // namespace

TEST(FrontElimination, RelaxesTheNodeThatCarriesTheResidualAloneAndLowersTheEnergy)
{
  AdheringBar bar;
  auto equilibrium = bar.lifted();
  const auto reference = bar.solve(*equilibrium, solvers::EliminationUse::never);
  ASSERT_TRUE(reference.converged) << reference.failure;

  auto x = bar.pushed(*equilibrium, 0.15);
  discretization::Vector f(bar.system->owned_map());
  const double pushed_energy = bar.model->evaluate(*x, &f, false).energy();
  const double pushed_residual = f.norm2();
  ASSERT_GT(pushed_residual, 1e-3);   // nN: far from equilibrium
  const discretization::Vector before(*x, Teuchos::Copy);

  solvers::FrontEliminationParameters parameters;
  parameters.use = solvers::EliminationUse::before_direction;
  parameters.node_share = 0.5;
  solvers::EliminationCounts counts;
  ASSERT_TRUE(solvers::relax_front(*bar.model, *x, f, parameters, counts));
  EXPECT_EQ(counts.applications, 1);
  EXPECT_GE(counts.local_iterations, 1);
  EXPECT_LE(counts.last_nodes, 2);   // the pushed node (and at most one neighbour whose residual it raised)
  EXPECT_LT(counts.last_reduction, 1.0);

  // Only the relaxed nodes' unknowns moved.
  discretization::Vector moved(*x, Teuchos::Copy);
  moved.update(-1.0, before, 1.0);
  const auto values = moved.getData();
  int changed = 0;
  for (decltype(values.size()) i = 0; i < values.size(); ++i) changed += values[i] != 0.0;
  int total = 0;
  Teuchos::reduceAll(*bar.system->owned_map()->getComm(), Teuchos::REDUCE_SUM, 1, &changed, &total);
  EXPECT_GE(total, 1);
  EXPECT_LE(total, 3 * counts.last_nodes);

  // f holds the relaxed state's residual; the energy fell.
  discretization::Vector check(bar.system->owned_map());
  const double relaxed_energy = bar.model->evaluate(*x, &check, false).energy();
  check.update(-1.0, f, 1.0);
  EXPECT_EQ(check.normInf(), 0.0);
  EXPECT_LT(relaxed_energy, pushed_energy);
  EXPECT_LT(f.norm2(), pushed_residual);
}

TEST(FrontElimination, NewtonWithTheRelaxationReachesTheSameEquilibrium)
{
  AdheringBar bar;
  auto reference = bar.lifted();
  const auto plain = bar.solve(*reference, solvers::EliminationUse::never);
  ASSERT_TRUE(plain.converged) << plain.failure;
  EXPECT_EQ(plain.elimination.applications, 0);
  for (const auto use : {solvers::EliminationUse::before_direction, solvers::EliminationUse::after_full_step}) {
    auto x = bar.pushed(*reference, 0.15);
    const auto result = bar.solve(*x, use);
    ASSERT_TRUE(result.converged) << result.failure;
    EXPECT_LT(relative_difference(*reference, *x), 1e-8);
    if (use == solvers::EliminationUse::before_direction) {
      EXPECT_GE(result.elimination.applications, 1);
    }
  }
}
