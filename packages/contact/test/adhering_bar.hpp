#pragma once
// A soft bar (Neo-Hookean, nu = 0) whose bottom face adheres to a flat substrate by the Lennard-Jones law and whose
// rigid top face is lifted: the analytic model (uniaxial stretch s, one gap g everywhere; pull_off_fold_test.cpp's
// header has its equations) and the finite element model on a 1 x 1 x 8 box mesh with its Newton solver, for the
// tests of the load path and of the energy minimizer.
#include "contact/adhesion.hpp"
#include "discretization/system_fields.hpp"
#include "mesh/box_mesh.hpp"
#include "solvers/newton.hpp"

#include <Teuchos_DefaultComm.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

namespace spatula::test {

struct AnalyticBar {
  contact::LennardJones law;
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
inline double bisect(const std::function<double(double)>& f, double a, double b)
{
  const bool rising = f(a) < 0.0;
  for (int k = 0; k < 200; ++k) {
    const double middle = 0.5 * (a + b);
    ((f(middle) < 0.0) == rising ? a : b) = middle;
  }
  return 0.5 * (a + b);
}

struct AdheringBar {
  static constexpr double side = 4.0;
  AnalyticBar bar;
  double work_of_adhesion = 0.0;   // of the law [nN/nm]
  mesh::HexMesh mesh;
  Teuchos::RCP<discretization::DiscreteSystem> system;
  std::unique_ptr<solvers::LinearSolverFactory> linear;
  Teuchos::RCP<solvers::SpatulaModel> model;
  std::unique_ptr<solvers::NewtonSolver> newton;

  explicit AdheringBar(const solvers::NewtonParameters& newton_parameters = {})
  {
    mesh::BoxParameters box;
    box.lengths = {side, side, bar.height};
    box.elements = {1, 1, 8};
    mesh = mesh::box_mesh(box);
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
    work_of_adhesion = adhesion.lennard_jones.work_of_adhesion();
    discretization::SolidParameters solid;
    solid.young = 2.0 * bar.mu;
    solid.poisson = 0.0;

    auto comm = Teuchos::DefaultComm<int>::getComm();
    const auto partition = mesh::partition_mesh(mesh, comm->getSize());
    system = Teuchos::rcp(new discretization::DiscreteSystem(
        mesh, partition, constraints, solid, comm, {adhesion.enrichment, contact::make_contact_model(adhesion)}));
    // Refactoring by count (lag), not by measured time (cost, the default): the path must not depend on the load
    // of the machine. (With cost, once, beside a long run, Newton converged across the snap within the smallest
    // step, and there was no descent to count.)
    solvers::LinearSolverParameters linear_parameters;
    linear_parameters.refactor = solvers::RefactorRule::lag;
    linear = std::make_unique<solvers::LinearSolverFactory>(linear_parameters);
    model = Teuchos::rcp(new solvers::SpatulaModel(system, linear->lows_factory()));
    newton = std::make_unique<solvers::NewtonSolver>(model, newton_parameters, *linear);
  }
};

// The bar translated rigidly by d along Z (the top face's lift master with it).
inline Teuchos::RCP<discretization::Vector> translated(const AdheringBar& bar, double d)
{
  auto x = bar.system->create_vector();
  std::vector<double> u(3 * bar.mesh.node_count(), 0.0);
  for (std::int64_t n = 0; n < bar.mesh.node_count(); ++n) u[3 * n + 2] = d;
  discretization::set_displacements(*bar.system, *x, u);
  bar.system->set_master(*x, discretization::Master::lift, d);
  return x;
}

}  // namespace spatula::test
