#include "peel/strip_peel.hpp"

#include "mesh/box_mesh.hpp"
#include "analysis/load_stepping.hpp"

#include <cmath>

namespace spatula::peel {

using discretization::Master;

StripPeelResult peel_strip(const StripPeelParameters& p, Teuchos::RCP<const Teuchos::Comm<int>> comm)
{
  mesh::BoxParameters box;
  box.lengths = {p.length, p.half_width, p.thickness};
  box.elements = {p.elements_along, 1, p.layers};
  const auto mesh = mesh::box_mesh(box);
  const double theta = p.angle_degrees * M_PI / 180.0;
  discretization::Constraints constraints;
  constraints.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
  if (p.law != "stiction") {   // without stiction the far end must be held against sliding
    std::vector<std::int64_t> far_end;
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      if (mesh.coordinates[n][0] == 0.0) far_end.push_back(n);
    constraints.fixed.push_back({far_end, 0});
  }
  constraints.rigid_nodes = mesh.nodes(mesh::Boundary::end_face);
  constraints.rigid_centre = {p.length, 0.0, 0.5 * p.thickness};
  constraints.lift_direction = {std::cos(theta), 0.0, std::sin(theta)};
  constraints.slide_direction = {-std::sin(theta), 0.0, std::cos(theta)};

  contact::AdhesionSettings s;
  s.law = p.law;
  s.enrichment = p.enrichment;
  s.quadrature = p.quadrature;
  s.lennard_jones.r_reg = 0.8 * s.lennard_jones.equilibrium_gap();
  s.lennard_jones.r_cut = 10.0;
  s.substrate_height = -s.lennard_jones.equilibrium_gap();
  const auto partition = mesh::partition_mesh(mesh, comm->getSize());
  discretization::SolidParameters solid;
  solid.young = p.young;
  auto system = Teuchos::rcp(new discretization::DiscreteSystem(mesh, partition, constraints, solid, comm,
                                                                {s.enrichment, contact::make_contact_model(s)}));
  solvers::LinearSolverFactory linear(solvers::LinearSolverParameters{});
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  solvers::NewtonParameters newton_parameters;
  newton_parameters.maximum_iterations = 40;
  newton_parameters.non_contracting_iterations = 0;   // the slow iterations at the peel front are needed
  newton_parameters.short_steps = 0;   // ... and so are the damped ones: the line search cuts steps there too
  solvers::NewtonSolver newton(model, newton_parameters, linear);
  analysis::LoadPath path(*model, newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = 0.25;
  steps.maximum = p.maximum_step;
  steps.minimum = 1e-3;
  discretization::MasterControl control;
  control.prescribed = {false, true, false};   // free rotation and sideways motion
  const auto failure = path.advance(Master::lift, p.pull, control, steps, 1.0, {});

  StripPeelResult result;
  result.completed = !failure.has_value();
  if (failure) result.failure = failure->reason;
  const double w = s.lennard_jones.work_of_adhesion(), a = 1.0 / (2.0 * p.young * p.thickness);
  const double c = 1.0 - std::cos(theta);
  result.energy_balance = (-c + std::sqrt(c * c + 4.0 * a * w)) / (2.0 * a);
  double sum = 0.0, weight = 0.0;
  const auto& points = path.points();
  for (std::size_t k = 0; k < points.size(); ++k) {
    result.curve.emplace_back(points[k].lift, points[k].force / p.half_width);
    if (k == 0 || points[k - 1].lift < p.window_start) continue;
    sum += 0.5 * (points[k - 1].force + points[k].force) / p.half_width * (points[k].lift - points[k - 1].lift);
    weight += points[k].lift - points[k - 1].lift;
  }
  result.steady_force_per_width = weight > 0.0 ? sum / weight : 0.0;
  return result;
}

}  // namespace spatula::peel
