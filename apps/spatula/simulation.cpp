#include "simulation.hpp"
#include "run.hpp"

#include "interruption.hpp"
#include "progress_report.hpp"
#include "pull_directions.hpp"

#include "discretization/system_fields.hpp"
#include "io/checked_write.hpp"
#include "solvers/node_blocks.hpp"
#include "solvers/out_of_memory.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <iomanip>

namespace spatula::app {

namespace {

discretization::SystemOptions system_options(const Scene& scene)
{
  discretization::SystemOptions options;
  options.enrichment = enrichment_of(scene);
  options.contact = scene.adhesion.model;
  return options;
}

Teuchos::RCP<discretization::DiscreteSystem> make_system(const Scene& scene, const geometry::SpatulaShape& shape,
                                                         const mesh::HexMesh& mesh, const mesh::Partition& partition,
                                                         Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                                         const discretization::SystemOptions& options)
{
  const auto p1 = shape.point(1);
  auto constraints =
      discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, scene.loading.hold_contact_surface);
  const auto directions = PullDirections::at(scene.loading.pull_angle);
  constraints.lift_direction = directions.lift;
  constraints.slide_direction = directions.slide;
  return Teuchos::rcp(new discretization::DiscreteSystem(mesh, partition, constraints, scene.material, comm, options));
}

}  // namespace

Run::Run(const Scene& scene, const geometry::SpatulaShape& shape, const mesh::HexMesh& mesh,
         const mesh::Partition& partition, Teuchos::RCP<const Teuchos::Comm<int>> comm,
         const io::OutputDirectory* directory, io::XdmfOutput* fields, std::ostream& out)
    : scene_(scene), mesh_(mesh), comm_(comm), root_(comm->getRank() == 0), directory_(directory), fields_(fields),
      out_(out), options_(system_options(scene)), system_(make_system(scene, shape, mesh, partition, comm, options_)),
      linear_(scene.linear_solver, scene.linear_solver.type == solvers::LinearSolverType::gmres_amg
                                       ? std::make_shared<const solvers::NodeBlocks>(solvers::node_blocks(*system_))
                                       : nullptr),
      model_(Teuchos::rcp(new solvers::SpatulaModel(system_, linear_.lows_factory()))),
      newton_(model_, scene.newton, linear_),
      path_(*model_, newton_, root_ ? &out : nullptr, scene.output.convergence_tables), theta_s_(shape.theta_s()),
      young_(scene.material.young), initial_contact_(path_.last().contact_energy)
{
  path_.set_instability_policy(instability_policy(scene.loading));
  const auto& contact = options_.contact;
  if (contact) reference_energy_ = full_spatula(system_->contact_area()) * contact->work_of_adhesion();
  if (root_ && contact)
    out << "adhesion: " << contact->description() << "\n"
        << "  contact area A_c = " << full_spatula(system_->contact_area()) << " nm^2, Pi_c0 = A_c w_adh = "
        << reference_energy_ << " nN nm = " << reference_energy_ / young_ << " E R0^3\n";
  auto jump = scene.loading.jump;   // the step balance check in the half model's energy (adhesion only)
  jump.step_balance_tolerance = contact ? scene.loading.step_balance_tolerance * reference_energy_ / halves : 0.0;
  path_.set_jump_parameters(jump);
  path_.set_energy_report(halves, "full spatula");
  if (contact) path_.set_detachment_test([this](const analysis::LoadPoint& p) { return detached(p); });
  path_.set_descent_watch([this] { on_descent(); });
}

// Detachment ends a path cleanly: the moment (rotation) or the pull (lift) has collapsed to under 1 % of its peak
// with most of the pad released.
bool Run::detached(const analysis::LoadPoint& p)
{
  peak_moment_ = std::max(peak_moment_, p.moment);
  peak_force_ = std::max(peak_force_, p.force);
  peak_slide_ = std::max(peak_slide_, std::abs(p.slide_force));
  const Master moved = stage().master();
  const bool collapsed = moved == Master::rotation ? p.moment < 0.01 * peak_moment_
                         : moved == Master::lift  ? p.force < 0.01 * peak_force_
                                                  : std::abs(p.slide_force) < 0.01 * peak_slide_;
  return collapsed && released_fraction(p) > 0.5;
}

void Run::write_fields(const Vector& x, double time)
{
  io::FieldState state;
  state.time = time;
  state.displacement = discretization::node_displacements(*system_, x);
  auto trace = discretization::element_cauchy_trace(*system_, x);
  for (auto& value : trace) value /= young_;
  state.cell_scalars[stress_field] = std::move(trace);   // the paper's colour scale: tr(sigma) / E
  auto dissipation = discretization::element_contact_dissipation(*system_);
  if (!dissipation.empty()) state.cell_scalars[friction_field] = std::move(dissipation);
  if (fields_) fields_->add_state(state);
}

void Run::print_step(const analysis::LoadPoint& p)
{
  print_state_line(out_, p, stage().name, theta_s_, *curve_, options_.contact ? reference_energy_ : 0.0);
  // A curve whose energies do not balance is not to be trusted: say so once, when it first happens.
  if (options_.contact && !balance_warned_ && curve_->balance_error(p) > balance_limit) {
    balance_warned_ = true;
    out_ << "warning: at step " << p.step << " the energy balance error " << curve_->balance_error(p)
         << " Pi_c0 exceeds " << balance_limit << " (the paper's bound): the curve from here on is not reliable "
         << "(contact under-resolved? use Q1C2, more contact quadrature points or smaller steps)" << std::endl;
  }
}

void Run::on_point(const analysis::LoadPoint& p, const Vector& x)
{
  if (root_) {
    curve_->write(p, stage().name, theta_s_);
    print_step(p);
  }
  if (scene_.output.tangent_spectrum > 0) {
    if (!spectrum_)
      spectrum_ = std::make_unique<SpectrumOutput>(*system_, scene_.linear_solver.mumps, scene_.output.tangent_spectrum,
                                                   root_ && directory_ ? directory_->file("spectrum.csv") : "");
    spectrum_->write(p, stage().name.c_str(), load_of(p), x);
  }
  const int interval = scene_.output.field_interval;
  if (interval > 0 && p.step % interval == 0) write_fields(x, load_of(p));
  checkpoint_if_due(p, x);
  stop_if_interrupted(*comm_);   // a signal stops the run here, at a converged state, on every rank
}

// After every iteration of a jump's energy descent: the descent (an hour on the paper's mesh) is checkpointed with
// the last converged state when due, and a signal stops it, as after a converged step.
void Run::on_descent()
{
  checkpoint_if_due(path_.last(), path_.state());
  stop_if_interrupted(*comm_);
}

std::optional<Stop> Run::press_onto_rough_substrate()
{
  const auto& adhesion = scene_.adhesion.settings;
  if (!options_.contact || adhesion.substrate != contact::SubstrateKind::rough || !adhesion.conform ||
      !scene_.loading.restart_file.empty())
    return std::nullopt;
  // Every node column is shifted down by the depth of the surface below it (tapering to nothing along the first
  // 100 nm of the shaft), then equilibrium is found.
  std::vector<double> u(3 * mesh_.node_count(), 0.0);
  const double top = adhesion.rough.base + adhesion.rough.z0;
  for (std::int64_t n = 0; n < mesh_.node_count(); ++n) {
    const auto& X = mesh_.coordinates[n];
    const double weight = std::clamp(1.0 + X[0] / 100.0, 0.0, 1.0);
    double S, gradient[2], hessian[2][2];
    adhesion.rough.surface(X[0], X[1], S, gradient, hessian);
    u[3 * n + 2] = weight * (S - top);
  }
  auto guess = system_->create_vector();
  discretization::set_displacements(*system_, *guess, u);
  const auto failure =
      path_.equilibrate(*guess, scene_.loading.stages.front().control());
  if (failure) {   // before any load: the stage is the rotation's start, the reason says what failed
    auto pressing = *failure;
    pressing.reason = "pressing the pad onto the rough substrate: " + pressing.reason;
    return Stop{pressing, 0, false, scene_.loading.stages.front().name, scene_.loading.stages.front().master()};
  }
  if (root_) out_ << "pad pressed onto the rough substrate (z0 = " << adhesion.rough.z0 << " nm): equilibrium found\n";
  initial_contact_ = path_.last().contact_energy;   // the energies count from this state
  initial_internal_ = path_.last().internal_energy;
  return std::nullopt;
}

void Run::start()
{
  const auto& loading = scene_.loading;
  if (!loading.restart_file.empty()) {
    auto x = system_->create_vector();
    auto history = read_checkpoint(scene_, *system_, *x, path_stage_);
    const bool anchor = scene_.adhesion.settings.anchor_at_restart;
    if (anchor) {   // at the restart state (r_a = 0 there: the same energy and forces), or where the stopped run set them
      anchors_ = system_->create_vector();
      if (scene_.resume)
        read_anchors(scene_, *system_, *anchors_);
      else
        anchors_->assign(*x);
      system_->set_contact_anchors(*anchors_);
    }
    if (scene_.resume) {   // a stopped run goes on with its own baseline, peaks, wall time and increment
      const auto record = read_run_record(scene_);
      initial_internal_ = record.initial_internal_energy;
      initial_contact_ = record.initial_contact_energy;
      peak_moment_ = record.peak_moment;
      peak_force_ = record.peak_force;
      history.seconds = record.seconds;
      history.step_control = record.step_control;
    }
    path_.restart(*x, history, scene_.resume);
    if (root_)
      out_ << "restart from '" << restart_label(loading) << "' of " << loading.restart_file << " (step "
           << history.step << ", u_z " << history.lift << " nm"
           << (path_stage_.index > 0 ? ", in the " + stage().name : std::string()) << ")"
           << (!anchor        ? ""
               : scene_.resume ? "; contact anchors where the stopped run set them"
                               : "; contact anchors set at this state")
           << "\n";
    if (auto jump = read_jump_in_progress(scene_, *system_)) {
      if (root_)
        out_ << "  it was inside a jump past an instability (" << motion_name(jump->controlled) << " = "
             << (jump->controlled == Master::rotation ? (theta_s_ + jump->value) / degree : jump->value)
             << ", energy descent at iteration " << jump->iterations << ")\n";
      path_.resume_jump(std::move(*jump));
    }
  } else {   // the first stage begins at the start
    path_stage_ = PathStage{0, load_of(path_.last(), loading.stages.front())};
  }
  if (root_)
    curve_ = std::make_unique<CurveWriter>(directory_->file("curve.csv"), young_, reference_energy_,
                                           initial_internal_, initial_contact_, scene_.resume ? path_.last().step : -1,
                                           PullDirections::at(scene_.loading.pull_angle));
  if (!scene_.resume) {   // a resumed run has its starting state in its curve and fields already
    if (root_) curve_->write(path_.last(), stage().name, theta_s_);
    write_fields(path_.state(), (theta_s_ + path_.last().rotation) / degree);
  }
}

std::optional<analysis::Failure> Run::follow_load_path(int& interrupted_by)
{
  const auto& loading = scene_.loading;
  std::optional<analysis::Failure> failure;
  try {
    const auto& stages = loading.stages;
    for (auto index = static_cast<std::size_t>(path_stage_.index); index < stages.size(); ++index) {
      const Stage& stage = stages[index];
      if (path_stage_.index != static_cast<int>(index))   // entering it (a restart inside it keeps its start)
        path_stage_ = PathStage{static_cast<int>(index), load_of(path_.last(), stage)};
      const double target = stage.target + (stage.relative ? path_stage_.start : 0.0);
      bool detached = false;
      failure = follow_stage(stage, target, detached);
      if (failure || detached || paused()) return failure;
    }
  } catch (const Interrupted& signal) {
    cancel_watchdog();   // the converged state to stop at is reached
    interrupted_by = signal.signal;
    if (root_) out_ << "spatula: " << signal.what() << " at step " << path_.last().step << "; stopping\n";
  } catch (const solvers::OutOfMemory& error) {
    if (!error.collective()) throw;   // one rank alone: the others wait in a collective call (main ends them all)
    out_of_memory_ = true;
    const auto& last = path_.last();
    failure = analysis::Failure{last.step + 1, load_of(last), 0.0,
                                std::string(error.what()) + "; the job allows less memory than this mesh and "
                                "solver need: give it more, or choose a coarser mesh"};
  }
  return failure;
}

std::optional<analysis::Failure> Run::follow_stage(const Stage& stage, double target, bool& detached)
{
  const auto on_point = [this](const analysis::LoadPoint& p, const Vector& x) { this->on_point(p, x); };
  const auto& loading = scene_.loading;
  std::vector<double> stops;   // a rotation's checkpoint inclinations on the way, then its target
  if (stage.kind == StageKind::rotate && stage.checkpoints) {
    const double current = motion_of(path_.last(), Master::rotation);
    for (double c : loading.checkpoints)
      if (c > std::min(current, target) + 1e-9 && c < std::max(current, target) - 1e-9) stops.push_back(c);
    if (target < current) std::reverse(stops.begin(), stops.end());
  }
  stops.push_back(target);
  // The rotation counts in radians from theta_s; a force in the half model (the app's forces are the full spatula's).
  const double unit = stage.kind == StageKind::rotate ? degree : stage.force() ? 1.0 / halves : 1.0;
  const double offset = stage.kind == StageKind::rotate ? theta_s_ : 0.0;
  if (stage.stop_at_force != 0.0) {   // the stop rule: the force along the motion reaches its value
    const auto force_of = [&stage](const analysis::LoadPoint& p) {
      return full_spatula(p.reaction(stage.master()));
    };
    const double begun = force_of(path_.last()), threshold = stage.stop_at_force;
    path_.set_end_test([=](const analysis::LoadPoint& p) { return (force_of(p) - threshold) * (begun - threshold) <= 0.0; });
  }
  for (double stop : stops) {
    auto failure =
        stage.force()
            ? path_.advance_force(stage.master(), stop * unit, stage.control(), stage.steps, unit, on_point)
            : path_.advance(stage.master(), stop * unit - offset, stage.control(), stage.steps, unit, on_point);
    detached = path_.detached();
    if (failure || detached || path_.ended()) {
      path_.set_end_test(nullptr);
      if (path_.ended() && root_)
        out_ << "stage '" << stage.name << "' ends at its stop force " << stage.stop_at_force << " nN\n";
      return failure;
    }
    if (stage.kind == StageKind::rotate && stage.checkpoints &&
        std::find(loading.checkpoints.begin(), loading.checkpoints.end(), stop) != loading.checkpoints.end()) {
      write_checkpoint_at(stop);
      // --stop-after-checkpoint: the run stops here, unless its path ends here anyway
      const bool path_ends = stop == stops.back() && path_stage_.index + 1 == static_cast<int>(loading.stages.size());
      if (scene_.stop_after_checkpoint && checkpoint_label(*scene_.stop_after_checkpoint) == checkpoint_label(stop) &&
          !path_ends) {
        paused_at_ = stop;
        break;
      }
    }
  }
  path_.set_end_test(nullptr);
  return std::nullopt;
}

std::optional<Stop> Run::finish(std::optional<analysis::Failure> failure, int interrupted_by)
{
  // Under a dead load, no equilibrium at a larger force: the spatula detaches at the largest force it carries.
  if (!interrupted_by && failure && failure->largest_force && options_.contact) {
    if (root_)
      out_ << "detachment: under a prescribed force the end face carries at most " << load_of(path_.last())
           << " nN (" << stage().name << "); beyond it no state holds the load\n";
    failure.reset();
  }
  // No equilibrium beyond a state where most of the pad has let go, or a jump whose descent let go of the substrate
  // on the way (no contact point of its last state within the gap of the strongest attraction): the detachment.
  if (!interrupted_by && failure && !out_of_memory_ && options_.contact &&
      (released_fraction(path_.last()) > 0.5 || failure->let_go)) {
    if (root_)
      out_ << "detachment: no equilibrium beyond " << stage().name << " = " << failure->load << " ("
           << failure->reason << ")\n";
    failure.reset();
  } else if (path_.detached() && root_) {
    out_ << "detachment: the "
         << (stage().master() == Master::rotation ? "moment" : stage().master() == Master::lift ? "pull" : "X force")
         << " has collapsed\n";
  }
  const auto& last = path_.last();
  if (scene_.output.field_interval == 0 || last.step % scene_.output.field_interval != 0)
    write_fields(path_.state(), load_of(last));
  if (root_) {
    print_solver_counts(out_, *model_, linear_, path_);
  }
  if (!failure && !interrupted_by && !paused()) return std::nullopt;
  // The last converged state, to go on from (spatula --resume, or Loading/restart from = last state).
  Stop stop;
  stop.signal = interrupted_by;
  stop.paused = paused();
  stop.stage = stage().name;
  stop.moved = stage().master();
  stop.force = stage().force();
  if (failure && !out_of_memory_ && path_.jump_in_progress())   // a descent stopped at its iteration limit
    failure->reason += anchors_ ? "; the descent's state is checkpointed with the last state and the stiction anchors: "
                                  "resuming the run (spatula --resume) with a larger 'Loading/Jump/maximum iterations' "
                                  "goes on from there with the same anchors"
                                : "; the descent's state is checkpointed with the last state: resuming the run (spatula "
                                  "--resume) or a restart from it ('Loading/restart from' = 'last state'), with a larger "
                                  "'Loading/Jump/maximum iterations', goes on from there";
  if (failure) stop.failure = *failure;
  else if (paused())
    stop.failure = analysis::Failure{last.step, load_of(last), 0.0,
                                     "stopped as asked after writing the checkpoint '" + checkpoint_label(*paused_at_) +
                                         "' (--stop-after-checkpoint)"};
  else stop.failure = analysis::Failure{last.step, load_of(last), 0.0, Interrupted(interrupted_by).what()};
  auto point = last;   // after a pause the path goes on from a checkpoint inclination with a fresh step controller
  if (paused()) point.step_control = analysis::StepControllerState{};
  write_last_state(path_.state(), point);   // collective
  stop.checkpointed = true;
  return stop;
}

std::vector<std::string> cell_field_names(const Scene& scene)
{
  if (scene.adhesion.model && scene.adhesion.model->dissipated_index() >= 0) return {stress_field, friction_field};
  return {stress_field};
}

const char* motion_name(discretization::Master motion)
{
  return motion == discretization::Master::rotation ? "rotation" : motion == discretization::Master::lift ? "lift" : "slide";
}

std::optional<Stop> run_simulation(const Scene& scene, const geometry::SpatulaShape& shape, const mesh::HexMesh& mesh,
                                   const mesh::Partition& partition, Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                   const io::OutputDirectory* directory, io::XdmfOutput* fields, std::ostream& out)
{
  Run run(scene, shape, mesh, partition, comm, directory, fields, out);
  if (auto stop = run.press_onto_rough_substrate()) return stop;
  run.start();
  int interrupted_by = 0;
  auto failure = run.follow_load_path(interrupted_by);
  return run.finish(std::move(failure), interrupted_by);
}

}  // namespace spatula::app
