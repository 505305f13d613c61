#include "newton.hpp"
#include "spatula_mesher.hpp"
#include <Teuchos_DefaultComm.hpp>
#include <gtest/gtest.h>
#include <iostream>
TEST(Newton, SpatulaRotationSmoke)
{
  using namespace spatula;
  const geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  const auto mesh = mesh::mesh_spatula(shape, mesh::MeshParameters{});
  auto comm = Teuchos::DefaultComm<int>::getComm();
  const auto partition = mesh::partition_mesh(mesh, comm->getSize());
  const auto p1 = shape.point(1);
  auto system = Teuchos::rcp(new discretization::DiscreteSystem(mesh, partition, discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, true), {}, comm));
  solvers::LinearSolverFactory linear(solvers::LinearSolverParameters{});
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  solvers::NewtonSolver newton(model, solvers::NewtonParameters{}, linear);
  auto x = system->create_vector();
  system->set_master(*x, discretization::Master::rotation, 0.01);
  auto result = newton.solve(*x, comm->getRank() == 0 ? &std::cout : nullptr);
  EXPECT_TRUE(result.converged) << result.failure;
  auto e = system->evaluate(*x, nullptr, false);
  if (comm->getRank() == 0) std::cout << "moment " << e.master_residual[0] << " force " << e.master_residual[1] << " energy " << e.internal_energy << "\n";
}
