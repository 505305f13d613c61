// The solid solver on small models: a slender bar bent by end rotations against beam theory, the energy balance
// Pi_int = int M dtheta, quadratic Newton convergence at large rotation, the spatula's reactions on 1 vs 2 ranks, and a
// thin layer sheared by a slide of its rigid face against simple shear.
#include "mesh/box_mesh.hpp"
#include "analysis/load_stepping.hpp"
#include "mesh/spatula_mesher.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace spatula;
using analysis::LoadPath;
using discretization::Master;
using discretization::MasterControl;

namespace {

constexpr double pi = 3.14159265358979323846;

// A bar of length 2L along Z, bent by rotating its end faces about Y: by symmetry the model is a quarter (Z >= 0,
// Y >= 0), the face Z = L rotated rigidly about its centre with its lift free (no axial force), the mid-section
// Z = 0 held in Z. Uniform bending with curvature alpha / L.
struct Bar {
  double length = 100.0, width = 10.0, height = 10.0;   // full width (Y) and height (X, the bending direction)
  int elements_along = 80, elements_across = 2, elements_through = 4;
  mesh::HexMesh mesh;
  Bar()
  {
    mesh::BoxParameters box;
    box.lengths = {height, 0.5 * width, length};
    box.elements = {elements_through, elements_across, elements_along};
    mesh = mesh::box_mesh(box);
  }
  std::vector<std::int64_t> nodes_at_z(double z) const
  {
    std::vector<std::int64_t> nodes;
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      if (std::abs(mesh.coordinates[n][2] - z) < 1e-9) nodes.push_back(n);
    return nodes;
  }
  discretization::Constraints constraints() const
  {
    discretization::Constraints c;
    c.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
    c.fixed.push_back({nodes_at_z(0.0), 2});
    c.rigid_nodes = nodes_at_z(length);
    c.rigid_centre = {0.5 * height, 0.0, length};
    return c;
  }
};

struct Solver {
  Teuchos::RCP<discretization::DiscreteSystem> system;
  solvers::LinearSolverFactory linear;
  Teuchos::RCP<solvers::SpatulaModel> model;
  std::unique_ptr<solvers::NewtonSolver> newton;
  mesh::Partition partition;

  Solver(const mesh::HexMesh& mesh, const discretization::Constraints& constraints,
         Teuchos::RCP<const Teuchos::Comm<int>> comm, solvers::NewtonParameters newton_parameters = {},
         solvers::LinearSolverParameters linear_parameters = {})
      : linear(linear_parameters)
  {
    partition = mesh::partition_mesh(mesh, comm->getSize());
    system = Teuchos::rcp(new discretization::DiscreteSystem(mesh, partition, constraints, {}, comm));
    model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
    newton = std::make_unique<solvers::NewtonSolver>(model, newton_parameters, linear);
  }
};

}  // namespace

TEST(Bending, MomentMatchesBeamTheoryAndEnergyBalances)
{
  Bar bar;
  Solver solver(bar.mesh, bar.constraints(), Teuchos::DefaultComm<int>::getComm());
  LoadPath path(*solver.model, *solver.newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = 0.5;
  steps.maximum = 0.5;
  const double degree = pi / 180.0;
  ASSERT_FALSE(path.advance(Master::rotation, 2.0 * degree, MasterControl::moving(Master::rotation, {Master::lift}), steps, degree, {}).has_value());
  // Small strain: M = E I kappa with kappa = alpha / L, I = b h^3 / 12 (the model carries half of b). Trilinear
  // hexahedra with full integration lock a little in bending: +1.5 % with these elements (1.25 x 2.5, 4 through
  // the height), +3 % with twice as long ones.
  const auto& point = path.last();
  const double E = 2.0, kappa = point.rotation / bar.length;
  const double I = bar.width * std::pow(bar.height, 3) / 12.0;
  const double beam = E * I * kappa;
  const double model = 2.0 * point.moment;
  EXPECT_NEAR(model / beam, 1.0, 0.02) << "M = " << model << " beam theory " << beam;
  // Energy balance: Pi_int = int M dtheta (trapezoidal along the path).
  EXPECT_NEAR(point.internal_energy / point.external_work, 1.0, 1e-3);
  // No force along the bar (the lift is free).
  EXPECT_NEAR(point.force, 0.0, 1e-9);
}

TEST(Bending, LargeRotationEnergyBalanceAndQuadraticConvergence)
{
  Bar bar;
  solvers::NewtonParameters newton;
  newton.relative_tolerance = 1e-13;
  newton.absolute_tolerance = 1e-13;
  newton.update_tolerance = 1e-12;
  newton.inexact = false;   // Newton's own convergence: exact linear solves, a fresh factorization every tangent
  solvers::LinearSolverParameters exact;
  exact.refactor = solvers::RefactorRule::lag;
  exact.lag = 0;
  Solver solver(bar.mesh, bar.constraints(), Teuchos::DefaultComm<int>::getComm(), newton, exact);
  const double degree = pi / 180.0;
  LoadPath path(*solver.model, *solver.newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = 5.0;
  steps.maximum = 5.0;
  ASSERT_FALSE(path.advance(Master::rotation, 40.0 * degree, MasterControl::moving(Master::rotation, {Master::lift}), steps, degree, {}).has_value());
  EXPECT_NEAR(path.last().internal_energy / path.last().external_work, 1.0, 1e-3);

  // One more large step (40 -> 50 deg) from the converged state, without predictor: the
  // residual falls quadratically, |f_k+1| <= C |f_k|^2 once close.
  auto& x = path.state();
  solver.system->set_master(x, Master::rotation, 50.0 * degree);
  const auto result = solver.newton->solve(x, nullptr);
  ASSERT_TRUE(result.converged) << result.failure;
  std::vector<double> norms{result.initial_residual_norm};
  for (const auto& row : result.iterations) norms.push_back(row.residual_norm);
  if (Teuchos::DefaultComm<int>::getComm()->getRank() == 0) {
    std::cout << "residual sequence (40 -> 50 deg in one step):";
    for (double n : norms) std::cout << " " << n;
    std::cout << "\n";
  }
  ASSERT_GE(norms.size(), 4u);
  int quadratic = 0;
  for (std::size_t k = 1; k + 1 < norms.size(); ++k)
    if (norms[k] < 1e-2 * norms[0] && norms[k + 1] > 1e-12 * norms[0])
      quadratic += norms[k + 1] <= 10.0 * norms[k] * norms[k] / norms[0] ? 1 : 0;
  EXPECT_GE(quadratic, 1) << "no quadratic contraction seen";
  for (std::size_t k = 1; k < norms.size(); ++k) EXPECT_LT(norms[k], norms[k - 1]);
}

TEST(SpatulaRotation, SameReactionsOnAllRanksAndOnOne)
{
  const geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  const auto mesh = mesh::mesh_spatula(shape, mesh::MeshParameters{});
  const auto p1 = shape.point(1);
  const auto constraints = discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, true);
  const double degree = pi / 180.0;
  analysis::StepParameters steps;
  steps.initial = 2.5;
  steps.maximum = 2.5;
  std::vector<analysis::LoadPoint> results;
  for (auto comm : {Teuchos::DefaultComm<int>::getComm(),
                    Teuchos::RCP<const Teuchos::Comm<int>>(new Teuchos::MpiComm<int>(MPI_COMM_SELF))}) {
    Solver solver(mesh, constraints, comm);
    LoadPath path(*solver.model, *solver.newton, nullptr, false);
    ASSERT_FALSE(path.advance(Master::rotation, 10.0 * degree, MasterControl::moving(Master::rotation, {Master::lift}), steps, degree, {}).has_value());
    results.push_back(path.last());
  }
  EXPECT_NEAR(results[0].moment, results[1].moment, 1e-8 * std::abs(results[1].moment));
  EXPECT_NEAR(results[0].lift, results[1].lift, 1e-8 * std::abs(results[1].lift));
  EXPECT_NEAR(results[0].internal_energy, results[1].internal_energy, 1e-8 * results[1].internal_energy);
  EXPECT_GT(results[0].moment, 0.0);
  EXPECT_NEAR(results[0].force, 0.0, 1e-9);   // zero net Z force on the face: w is free
}

// A far too large first increment (the elements next to the rotated face would invert): the step is cut back
// until Newton converges, and every recorded state is finite.
TEST(Bending, OversizedStepsAreCutBackNeverAcceptedBroken)
{
  Bar bar;
  Solver solver(bar.mesh, bar.constraints(), Teuchos::DefaultComm<int>::getComm());
  LoadPath path(*solver.model, *solver.newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = 120.0;
  steps.maximum = 120.0;
  steps.minimum = 0.5;
  const double degree = pi / 180.0;
  ASSERT_FALSE(path.advance(Master::rotation, 120.0 * degree, MasterControl::moving(Master::rotation, {Master::lift}), steps, degree, {}).has_value());
  EXPECT_NEAR(path.last().rotation, 120.0 * degree, 1e-12);
  EXPECT_GT(path.points().size(), 3u);   // it had to take smaller steps
  for (const auto& point : path.points()) {
    EXPECT_TRUE(std::isfinite(point.moment));
    EXPECT_TRUE(std::isfinite(point.internal_energy));
  }
  EXPECT_NEAR(path.last().internal_energy / path.last().external_work, 1.0, 2e-3);
}

// When the increment cannot be made small enough the run stops with a diagnosis instead of accepting a state.
TEST(Bending, UnreachableLoadReportsTheFailure)
{
  Bar bar;
  solvers::NewtonParameters newton;
  newton.maximum_iterations = 1;   // Newton cannot converge in one iteration from any useful increment
  newton.relative_tolerance = 1e-14;
  newton.absolute_tolerance = 0.0;
  Solver solver(bar.mesh, bar.constraints(), Teuchos::DefaultComm<int>::getComm(), newton);
  LoadPath path(*solver.model, *solver.newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = 10.0;
  steps.minimum = 1.0;
  const double degree = pi / 180.0;
  const auto failure = path.advance(Master::rotation, 30.0 * degree, MasterControl::moving(Master::rotation, {Master::lift}), steps, degree, {});
  ASSERT_TRUE(failure.has_value());
  EXPECT_EQ(failure->step, 1);
  EXPECT_LT(failure->smallest_increment, 2.0);
  EXPECT_NE(failure->reason.find("no convergence"), std::string::npos) << failure->reason;
  EXPECT_EQ(path.points().size(), 1u);   // nothing accepted
}

// A slide of the rigid face: a thin layer (thickness H, a x a, the half a x a/2 modelled) bonded to a fixed base and
// sheared by sliding its top face along X by u, rotation and lift held. Away from its free edges the layer is in
// simple shear, whose Neo-Hookean shear stress is exactly mu u / H; the edges (a strip of about H out of a) lower the
// force by a few per cent. The X reaction follows mu A u / H within H / a, linearly in u (the second slide doubles it).
TEST(Shear, ASlideShearsALayerAsSimpleShearPredicts)
{
  const double a = 40.0, thickness = 2.0;
  mesh::BoxParameters box;
  box.lengths = {a, 0.5 * a, thickness};
  box.elements = {20, 10, 2};
  const auto mesh = mesh::box_mesh(box);
  discretization::Constraints constraints;
  constraints.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
  std::vector<std::int64_t> base, top;
  for (std::int64_t n = 0; n < mesh.node_count(); ++n) {
    if (std::abs(mesh.coordinates[n][2]) < 1e-9) base.push_back(n);
    if (std::abs(mesh.coordinates[n][2] - thickness) < 1e-9) top.push_back(n);
  }
  for (int component = 0; component < 3; ++component) constraints.fixed.push_back({base, component});
  constraints.rigid_nodes = top;
  constraints.rigid_centre = {0.5 * a, 0.0, thickness};
  Solver solver(mesh, constraints, Teuchos::DefaultComm<int>::getComm());
  LoadPath path(*solver.model, *solver.newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = steps.maximum = 0.01;
  const discretization::SolidParameters solid;
  const double mu = solid.young / (2.0 * (1.0 + solid.poisson)), area = 0.5 * a * a;
  double first_force = 0.0;
  for (double u : {0.02, 0.04}) {
    ASSERT_FALSE(path.advance(Master::slide, u, MasterControl::moving(Master::slide), steps, 1.0, {}).has_value());
    const auto& p = path.last();
    const double simple_shear = mu * area * u / thickness;
    EXPECT_NEAR(p.slide, u, 1e-12);
    EXPECT_LT(std::abs(p.slide_force), simple_shear);
    EXPECT_GT(std::abs(p.slide_force), (1.0 - thickness / a) * simple_shear) << "at u = " << u;
    std::cout << "slide " << u << " nm: X force " << std::abs(p.slide_force) << " nN, simple shear " << simple_shear
              << " nN\n";
    if (first_force == 0.0) first_force = std::abs(p.slide_force);
    else EXPECT_NEAR(std::abs(p.slide_force), 2.0 * first_force, 1e-3 * first_force);   // small strain: linear
  }
}
