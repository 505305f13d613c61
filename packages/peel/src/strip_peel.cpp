#include "peel/strip_peel.hpp"

#include "peel/peel_balance.hpp"
#include "mesh/box_mesh.hpp"
#include "analysis/load_stepping.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>

namespace spatula::peel {

using discretization::Master;

namespace {

// The strip with one contact law: its system, Newton solver and load path (the end face pulled along
// constraints.lift_direction).
struct Strip {
  Teuchos::RCP<discretization::DiscreteSystem> system;
  Teuchos::RCP<solvers::SpatulaModel> model;
  std::unique_ptr<solvers::LinearSolverFactory> linear;
  std::unique_ptr<solvers::NewtonSolver> newton;
  std::unique_ptr<analysis::LoadPath> path;
};

Strip make_strip(const mesh::HexMesh& mesh, const mesh::Partition& partition,
                 const discretization::Constraints& constraints, const contact::AdhesionSettings& settings,
                 double young, Teuchos::RCP<const Teuchos::Comm<int>> comm)
{
  Strip strip;
  discretization::SolidParameters solid;
  solid.young = young;
  const auto contact = contact::make_contact_model(settings);
  strip.system = Teuchos::rcp(new discretization::DiscreteSystem(mesh, partition, constraints, solid, comm,
                                                                 {settings.enrichment, contact}));
  solvers::LinearSolverParameters linear;
  linear.mumps.symmetric = contact->symmetric();   // adhesive friction: LU
  strip.linear = std::make_unique<solvers::LinearSolverFactory>(linear);
  strip.model = Teuchos::rcp(new solvers::SpatulaModel(strip.system, strip.linear->lows_factory()));
  solvers::NewtonParameters newton;
  newton.maximum_iterations = 40;
  newton.non_contracting_iterations = 0;   // the slow iterations at the peel front are needed
  newton.short_steps = 0;   // ... and so are the damped ones: the line search cuts steps there too
  strip.newton = std::make_unique<solvers::NewtonSolver>(strip.model, newton, *strip.linear);
  strip.path = std::make_unique<analysis::LoadPath>(*strip.model, *strip.newton, nullptr, false);
  return strip;
}

discretization::Constraints pulled_along(discretization::Constraints constraints, double angle)
{
  constraints.lift_direction = {std::cos(angle), 0.0, std::sin(angle)};
  constraints.slide_direction = {-std::sin(angle), 0.0, std::cos(angle)};
  return constraints;
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

StripPeelResult peel_strip(const StripPeelParameters& p, Teuchos::RCP<const Teuchos::Comm<int>> comm)
{
  if (!(p.pre_strain >= 0.0 && p.pre_strain < 0.5))
    throw std::invalid_argument("peel_strip: pre_strain = " + std::to_string(p.pre_strain) +
                                " must lie in [0, 0.5)");
  const bool pretension = p.pre_strain > 0.0;
  mesh::BoxParameters box;
  box.lengths = {p.length, p.half_width, p.thickness};
  box.elements = {p.elements_along, 1, p.layers};
  const auto mesh = mesh::box_mesh(box);
  const double theta = p.angle_degrees * M_PI / 180.0;
  discretization::Constraints constraints;
  constraints.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
  if (p.law != "stiction" || pretension) {   // without stiction (or to stretch it) the far end is held in X
    std::vector<std::int64_t> far_end;
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      if (mesh.coordinates[n][0] == 0.0) far_end.push_back(n);
    constraints.fixed.push_back({far_end, 0});
  }
  constraints.rigid_nodes = mesh.nodes(mesh::Boundary::end_face);
  constraints.rigid_centre = {p.length, 0.0, 0.5 * p.thickness};

  contact::AdhesionSettings s;
  s.law = p.law;
  s.friction = p.friction;
  s.enrichment = p.enrichment;
  s.quadrature = p.quadrature;
  s.lennard_jones.r_reg = 0.8 * s.lennard_jones.equilibrium_gap();
  s.lennard_jones.r_cut = 10.0;
  s.substrate_height = -s.lennard_jones.equilibrium_gap();
  const auto peel_constraints = pulled_along(constraints, theta);
  const auto partition = mesh::partition_mesh(mesh, comm->getSize());
  Strip peel = make_strip(mesh, partition, peel_constraints, s, p.young, comm);
  if (pretension && !peel.system->contact_model()->holds_tangentially())
    throw std::invalid_argument("peel_strip: a pre-strain needs a law that holds the strip along the substrate "
                                "(stiction or adhesive friction), not '" + p.law + "'");

  analysis::StepParameters steps;
  steps.initial = 0.25;
  steps.maximum = p.maximum_step;
  steps.minimum = 1e-3;
  discretization::MasterControl control;
  control.prescribed = {false, true, false};   // free rotation and sideways motion
  const auto law = laws::NeoHookean::from_young(p.young, peel.system->solid().poisson);
  StripPeelResult result;
  double start = 0.0;   // the lift where the peel begins
  if (pretension) {
    auto frictionless = s;
    frictionless.law = "frictionless";
    const auto stretch_constraints = pulled_along(constraints, 0.0);
    Strip stretch = make_strip(mesh, partition, stretch_constraints, frictionless, p.young, comm);
    if (const auto failure = stretch.path->advance(Master::lift, p.pre_strain * p.length, control, steps, 1.0, {})) {
      result.failure = "stretching the strip: " + failure->reason;
      return result;
    }
    // Away from its ends the stretched strip carries the end's pull in uniaxial tension.
    result.pre_stretch = uniaxial_stretch(law, stretch.path->last().force / (p.half_width * p.thickness));
    // The same unknowns (the same constraints): the state carries over, the masters re-expressed along the peel's
    // directions, and the law's anchors are set where the strip lies.
    const auto& from = stretch.path->state();
    auto x = peel.system->create_vector();
    Tpetra::deep_copy(*x, from);
    std::array<double, 3> travel{};
    for (int i = 0; i < 3; ++i)
      travel[i] = stretch.system->master(from, Master::lift) * stretch_constraints.lift_direction[i] +
                  stretch.system->master(from, Master::slide) * stretch_constraints.slide_direction[i];
    peel.system->set_master(*x, Master::lift, dot(travel, peel_constraints.lift_direction));
    peel.system->set_master(*x, Master::slide, dot(travel, peel_constraints.slide_direction));
    peel.system->set_contact_anchors(*x);
    if (const auto failure = peel.path->equilibrate(*x, control)) {
      result.failure = "bonding the stretched strip: " + failure->reason;
      return result;
    }
    start = peel.system->master(peel.path->state(), Master::lift);
  }
  const auto failure = peel.path->advance(Master::lift, start + p.pull, control, steps, 1.0, {});

  result.completed = !failure.has_value();
  if (failure) result.failure = failure->reason;
  result.energy_balance = steady_peel_force(law, {p.half_width, p.thickness}, s.lennard_jones.work_of_adhesion(),
                                            theta, result.pre_stretch);
  const auto& points = peel.path->points();
  result.sliding_dissipation = points.back().sliding - points.front().sliding;
  double sum = 0.0, weight = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double pulled = points[k].lift - start;
    result.curve.emplace_back(pulled, points[k].force / p.half_width);
    if (k == 0 || points[k - 1].lift - start < p.window_start) continue;
    sum += 0.5 * (points[k - 1].force + points[k].force) / p.half_width * (points[k].lift - points[k - 1].lift);
    weight += points[k].lift - points[k - 1].lift;
  }
  result.steady_force_per_width = weight > 0.0 ? sum / weight : 0.0;
  return result;
}

}  // namespace spatula::peel
