#include "simulation.hpp"

#include "checkpoint.hpp"
#include "interruption.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <iomanip>

namespace spatula::app {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double degree = pi / 180.0;

// curve.csv: one row per converged state, full-spatula values (the model is half of it).
// Energies in the paper's form: Pi_sa = Pi_c - Pi_c(start) (= Pi_c0 + Pi_c for the exact law), all over
// Pi_c0 = A_c w_adh; the balance error |Pi_ext - Pi_int - Pi_sa| / Pi_c0 (Pi_c0 = 1 without adhesion).
class CurveWriter {
public:
  // Energies are counted from a baseline state: the undeformed spatula, or (rough substrates) the pad pressed
  // onto the substrate, whose internal and adhesion energies are given here.
  // `resume_after`: go on with the curve of a stopped run, keeping its rows up to that step (-1: a new curve).
  CurveWriter(const std::string& file, double young, double reference_energy, double initial_internal_energy,
              double initial_contact_energy, int resume_after = -1)
      : young_(young), reference_(reference_energy), initial_internal_(initial_internal_energy),
        initial_contact_(initial_contact_energy)
  {
    if (resume_after >= 0) {
      keep_rows_up_to(file, resume_after);
      out_.open(file, std::ios::app);
      out_ << std::setprecision(10);
      return;
    }
    out_.open(file);
    out_ << "step,stage,theta_y_deg,u_z_nm,M_y_nNnm,M_y_per_ER0^3,P_z_nN,P_z_per_ER0^2,Pi_int_1e-18J,"
            "Pi_ext_1e-18J,Pi_c_1e-18J,Pi_sa_1e-18J,Pi_ext_per_Pi_c0,Pi_int_per_Pi_c0,Pi_sa_per_Pi_c0,"
            "dissipated_per_Pi_c0,balance_error_per_Pi_c0,after_jump,contact_faces_active,contact_faces_skipped,"
            "newton_iterations,negative_pivots,wall_s,u_x_nm\n";
    out_ << std::setprecision(10);
  }
  double stored_adhesion(const analysis::LoadPoint& p) const { return 2 * (p.contact_energy - initial_contact_); }
  double internal(const analysis::LoadPoint& p) const { return 2 * (p.internal_energy - initial_internal_); }
  // |Pi_ext - Pi_int - Pi_sa - D| / Pi_c0 with D the energy the jumps past instabilities released (dissipated).
  double balance_error(const analysis::LoadPoint& p) const
  {
    return std::abs(2 * p.external_work - internal(p) - stored_adhesion(p) - 2 * p.dissipated) / reference_;
  }
  void write(const analysis::LoadPoint& p, const char* stage, double theta_s)
  {
    const double sa = stored_adhesion(p);
    out_ << p.step << "," << stage << "," << (theta_s + p.rotation) / degree << "," << p.lift << ","
         << 2 * p.moment << "," << 2 * p.moment / young_ << "," << 2 * p.force << "," << 2 * p.force / young_ << ","
         << internal(p) << "," << 2 * p.external_work << "," << 2 * p.contact_energy << "," << sa << ","
         << 2 * p.external_work / reference_ << "," << internal(p) / reference_ << "," << sa / reference_
         << "," << 2 * p.dissipated / reference_ << "," << balance_error(p) << "," << (p.after_jump ? 1 : 0) << ","
         << p.active_faces << "," << p.skipped_faces << ","
         << p.newton_iterations << "," << p.negative_pivots << "," << p.seconds << "," << p.slide << "\n";
    out_.flush();
  }

private:
  // Rewrites the curve with its header and the rows of steps up to `last_step` (a stopped run's rows past its
  // checkpoint are computed again).
  static void keep_rows_up_to(const std::string& file, int last_step)
  {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot resume: '" + file + "' is missing");
    std::string line, kept;
    for (bool header = true; std::getline(in, line); header = false)
      if (header || (!line.empty() && std::stoi(line.substr(0, line.find(','))) <= last_step)) kept += line + "\n";
    in.close();
    std::ofstream(file + ".writing") << kept;
    std::filesystem::rename(file + ".writing", file);
  }

  std::ofstream out_;
  double young_, reference_, initial_internal_, initial_contact_;
};

}  // namespace

const char* stage_name(discretization::Master stage)
{
  return stage == discretization::Master::rotation ? "rotation" : stage == discretization::Master::lift ? "lift" : "slide";
}

std::optional<Stop> run_simulation(const Scene& scene, const geometry::SpatulaShape& shape,
                                                const mesh::HexMesh& mesh, const mesh::Partition& partition,
                                                Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                                const io::OutputDirectory* directory, io::XdmfOutput* fields,
                                                std::ostream& out)
{
  const bool root = comm->getRank() == 0;
  const auto p1 = shape.point(1);
  const auto constraints =
      discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, scene.loading.hold_contact_surface);
  discretization::SystemOptions options;
  options.enrichment = enrichment_of(scene);
  if (scene.adhesion.enabled) options.contact = contact::make_contact_model(scene.adhesion.settings);
  auto system =
      Teuchos::rcp(new discretization::DiscreteSystem(mesh, partition, constraints, scene.material, comm, options));
  solvers::LinearSolverFactory linear(scene.linear_solver);
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  solvers::NewtonSolver newton(model, scene.newton, linear);
  analysis::LoadPath path(*model, newton, root ? &out : nullptr, scene.output.convergence_tables);
  if (scene.loading.past_instabilities == analysis::LoadPath::PastFolds::arc_length)
    path.enable_arc_length(scene.loading.arc_length_steps);
  else
    path.set_past_folds(scene.loading.past_instabilities);

  const double theta_s = shape.theta_s(), young = scene.material.young;
  // Pi_c0 = A_c w_adh of the full spatula, with A_c the meshed contact area.
  const double reference_energy =
      options.contact ? 2.0 * system->contact_area() * options.contact->work_of_adhesion() : 1.0;
  if (root && options.contact)
    out << "adhesion: " << options.contact->description() << "\n"
        << "  contact area A_c = " << 2.0 * system->contact_area() << " nm^2, Pi_c0 = A_c w_adh = " << reference_energy
        << " nN nm = " << reference_energy / young << " E R0^3\n";
  auto jump = scene.loading.jump;   // the step balance check in the half model's energy (adhesion only)
  jump.step_balance_tolerance = options.contact ? scene.loading.step_balance_tolerance * reference_energy / 2.0 : 0.0;
  path.set_jump_parameters(jump);
  std::unique_ptr<CurveWriter> curve;
  discretization::Master stage = discretization::Master::rotation;
  PathStage path_stage;   // where the path is: rotation, or lift from where
  // The energies the curve counts from (the undeformed spatula, or the pad pressed onto a rough substrate) and the
  // peaks the detachment test compares with: kept in every checkpoint, so that a resumed run goes on with them.
  double initial_contact = path.last().contact_energy, initial_internal = 0.0;
  double peak_moment = 0.0, peak_force = 0.0;
  auto write_fields = [&](const discretization::Vector& x, double time) {
    io::FieldState state;
    state.time = time;
    state.displacement = system->node_displacements(x);
    auto trace = system->element_cauchy_trace(x);
    for (auto& value : trace) value /= young;
    state.cell_scalars["I1"] = std::move(trace);   // the paper's colour scale: tr(sigma) / E
    if (fields) fields->add_state(state);
  };
  // The last converged state, as 'last state' with the run record (collective).
  auto write_last_state = [&](const discretization::Vector& x, const analysis::LoadPoint& p) {
    const RunRecord record{initial_internal, initial_contact, peak_moment, peak_force, p.seconds,
                           fields ? fields->state_count() : 0, p.step_control};
    write_checkpoint(directory ? directory->file("checkpoints.h5") : "", last_state_label, *system, x, p, path_stage,
                     scene, record);
  };
  using clock = std::chrono::steady_clock;
  auto last_checkpoint = clock::now();
  constexpr double balance_limit = 2e-3;   // |Pi_ext - Pi_int - Pi_sa - D| / Pi_c0, the paper's bound
  bool balance_warned = false;
  auto on_point = [&](const analysis::LoadPoint& p, const discretization::Vector& x) {
    if (root) {
      curve->write(p, stage_name(stage), theta_s);
      const std::ios_base::fmtflags flags = out.flags();
      const std::streamsize precision = out.precision();
      out << "step " << std::setw(4) << p.step << "  " << stage_name(stage) << "  theta_y " << std::fixed << std::setprecision(3)
          << std::setw(8) << (theta_s + p.rotation) / degree << " deg  u_z " << std::setw(9) << p.lift
          << " nm  M_y " << std::setprecision(4) << std::setw(10) << 2 * p.moment << " nN nm  P_z " << std::setw(9)
          << 2 * p.force << " nN  Pi_int " << std::setw(9) << curve->internal(p);
      if (options.contact)
        out << "  Pi_sa/Pi_c0 " << std::setprecision(4) << curve->stored_adhesion(p) / reference_energy
            << "  balance " << std::scientific << std::setprecision(1) << curve->balance_error(p) << std::fixed
            << "  faces " << p.active_faces << "+" << p.skipped_faces;
      out << "  newton "
          << p.newton_iterations << "  neg.piv " << p.negative_pivots << "  " << std::setprecision(1)
          << p.seconds << " s" << std::endl;
      out.flags(flags);   // the step line's format stays with it
      out.precision(precision);
      // A curve whose energies do not balance is not to be trusted: say so once, when it first happens.
      if (options.contact && !balance_warned && curve->balance_error(p) > balance_limit) {
        balance_warned = true;
        out << "warning: at step " << p.step << " the energy balance error " << curve->balance_error(p)
            << " Pi_c0 exceeds " << balance_limit << " (the paper's bound): the curve from here on is not reliable "
            << "(contact under-resolved? use Q1C2, more contact quadrature points or smaller steps)" << std::endl;
      }
    }
    const int interval = scene.output.field_interval;
    if (interval > 0 && p.step % interval == 0)
      write_fields(x, stage == discretization::Master::rotation ? (theta_s + p.rotation) / degree : p.lift);
    // Every 'Output/checkpoint interval' minutes of wall time, the state to resume from if the run is killed.
    if (scene.output.checkpoint_minutes > 0.0) {
      int due = root && clock::now() - last_checkpoint > std::chrono::duration<double>(60.0 * scene.output.checkpoint_minutes);
      Teuchos::broadcast(*comm, 0, Teuchos::outArg(due));
      if (due) {
        write_last_state(x, p);
        last_checkpoint = clock::now();
        if (root) out << "checkpoint '" << last_state_label << "' written at step " << p.step << std::endl;
      }
    }
    stop_if_interrupted(*comm);   // a signal stops the run here, at a converged state, on every rank
  };

  // Detachment ends a path cleanly: the moment (rotation) or the pull (lift) has collapsed to under 1 % of its peak
  // with most of the pad released.
  auto released_fraction = [&](const analysis::LoadPoint& p) {
    return 2.0 * (p.contact_energy - initial_contact) / reference_energy;
  };
  if (options.contact)
    path.set_detachment_test([&](const analysis::LoadPoint& p) {
      peak_moment = std::max(peak_moment, p.moment);
      peak_force = std::max(peak_force, p.force);
      const bool collapsed = stage == discretization::Master::rotation ? p.moment < 0.01 * peak_moment
                                                               : p.force < 0.01 * peak_force;
      return collapsed && released_fraction(p) > 0.5;
    });

  using analysis::LoadPath;
  using discretization::Master;
  const auto& loading = scene.loading;
  // On a rough substrate the pad starts pressed onto it: every node column is shifted down by the depth of the
  // surface below it (tapering to nothing along the first 100 nm of the shaft), then equilibrium is found.
  const auto& adhesion = scene.adhesion.settings;
  if (options.contact && adhesion.substrate == contact::SubstrateKind::rough && adhesion.conform && loading.restart_file.empty()) {
    std::vector<double> u(3 * mesh.node_count(), 0.0);
    const double top = adhesion.rough.base + adhesion.rough.z0;
    for (std::int64_t n = 0; n < mesh.node_count(); ++n) {
      const auto& X = mesh.coordinates[n];
      const double weight = std::clamp(1.0 + X[0] / 100.0, 0.0, 1.0);
      double S, gradient[2], hessian[2][2];
      adhesion.rough.surface(X[0], X[1], S, gradient, hessian);
      u[3 * n + 2] = weight * (S - top);
    }
    auto guess = system->create_vector();
    system->set_displacements(*guess, u);
    const auto failure = path.equilibrate(*guess, LoadPath::spatula_control(Master::rotation, loading.free_lift));
    if (failure) {   // before any load: the stage is the rotation's start, the reason says what failed
      auto pressing = *failure;
      pressing.reason = "pressing the pad onto the rough substrate: " + pressing.reason;
      return Stop{pressing, 0, false, Master::rotation};
    }
    if (root) out << "pad pressed onto the rough substrate (z0 = " << adhesion.rough.z0 << " nm): equilibrium found\n";
    initial_contact = path.last().contact_energy;   // the energies count from this state
    initial_internal = path.last().internal_energy;
  }
  if (!loading.restart_file.empty()) {
    auto x = system->create_vector();
    auto history = read_checkpoint(scene, *system, *x, path_stage);
    if (adhesion.anchor_at_restart) system->set_contact_anchors(*x);   // r_a = 0 here: the same energy and forces
    if (scene.resume) {   // a stopped run goes on with its own baseline, peaks, wall time and increment
      const auto record = read_run_record(scene);
      initial_internal = record.initial_internal_energy;
      initial_contact = record.initial_contact_energy;
      peak_moment = record.peak_moment;
      peak_force = record.peak_force;
      history.seconds = record.seconds;
      history.step_control = record.step_control;
    }
    path.restart(*x, history, scene.resume);
    if (path_stage.lifting) stage = discretization::Master::lift;
    if (root)
      out << "restart from '" << restart_label(loading) << "' of " << loading.restart_file << " (step "
          << history.step << ", u_z " << history.lift << " nm" << (path_stage.lifting ? ", in the lift" : "") << ")"
          << (adhesion.anchor_at_restart ? "; stiction anchors set at this state" : "") << "\n";
  }
  if (root)
    curve = std::make_unique<CurveWriter>(directory->file("curve.csv"), young, reference_energy, initial_internal,
                                          initial_contact, scene.resume ? path.last().step : -1);
  if (!scene.resume) {   // a resumed run has its starting state in its curve and fields already
    if (root) curve->write(path.last(), stage_name(stage), theta_s);
    write_fields(path.state(), (theta_s + path.last().rotation) / degree);
  }
  // The rotation, stopping at every checkpoint inclination on the way, then the lift. A signal ends either at a
  // converged state (Interrupted, on every rank together).
  std::optional<analysis::Failure> failure;
  int interrupted_by = 0;
  try {
    std::vector<double> stops;
    const double current = (theta_s + path.last().rotation) / degree;
    for (double c : loading.checkpoints)
      if (c > current + 1e-9 && c < loading.theta_y - 1e-9) stops.push_back(c);
    if (!path_stage.lifting) stops.push_back(loading.theta_y);
    for (double stop : stops) {
      failure = path.advance(Master::rotation, stop * degree - theta_s,
                             LoadPath::spatula_control(Master::rotation, loading.free_lift), loading.rotation_steps,
                             degree, on_point);
      if (failure || path.detached()) break;
      if (std::find(loading.checkpoints.begin(), loading.checkpoints.end(), stop) != loading.checkpoints.end()) {
        write_checkpoint(directory ? directory->file("checkpoints.h5") : "", checkpoint_label(stop), *system,
                         path.state(), path.last(), path_stage, scene,
                         RunRecord{initial_internal, initial_contact, peak_moment, peak_force, path.last().seconds,
                                   fields ? fields->state_count() : 0, path.last().step_control});
        if (root) out << "checkpoint " << checkpoint_label(stop) << " written\n";
      }
    }
    if (!failure && !path.detached() && loading.type == LoadingType::lift) {
      stage = Master::lift;
      if (!path_stage.lifting) path_stage = PathStage{true, path.last().lift};
      const double target = loading.final_lift + (loading.lift_relative ? path_stage.lift_start : 0.0);
      auto control = LoadPath::spatula_control(Master::lift, false);
      control.prescribed[static_cast<int>(Master::slide)] = !loading.free_slide;
      failure = path.advance(Master::lift, target, control, loading.lift_steps, 1.0, on_point);
    }
  } catch (const Interrupted& signal) {
    interrupted_by = signal.signal;
    if (root) out << "spatula: " << signal.what() << " at step " << path.last().step << "; stopping\n";
  }
  // No equilibrium beyond a state where most of the pad has let go: that is the detachment.
  if (!interrupted_by && failure && options.contact && released_fraction(path.last()) > 0.5) {
    if (root)
      out << "detachment: no equilibrium beyond " << stage_name(stage) << " = " << failure->load << " (" << failure->reason
          << ")\n";
    failure.reset();
  } else if (path.detached() && root) {
    out << "detachment: the " << (stage == Master::rotation ? "moment" : "pull") << " has collapsed\n";
  }
  const auto& last = path.last();
  if (scene.output.field_interval == 0 || last.step % scene.output.field_interval != 0)
    write_fields(path.state(), stage == Master::rotation ? (theta_s + last.rotation) / degree : last.lift);
  if (root) {
    const auto& statistics = linear.mumps_statistics();
    out << "solver: " << model->counters().jacobians << " tangents, " << model->counters().residuals
        << " residual-only evaluations, " << model->counters().inadmissible << " inadmissible trial states";
    if (statistics.factorizations > 0)
      out << "; MUMPS: " << statistics.analyses << " analyses, " << statistics.factorizations << " factorizations (" << statistics.reused << " tangents served by an earlier one, "
          << statistics.factorization_seconds << " s), " << statistics.solves << " solves";
    if (const auto* descents = path.descent_statistics())
      out << "; jumps' energy descents: " << descents->analyses << " analyses, " << descents->factorizations
          << " factorizations (" << descents->factorization_seconds << " s), " << descents->solves << " solves";
    out << "\n";
  }
  if (!failure && !interrupted_by) return std::nullopt;
  // The last converged state, to go on from (Loading/restart from = last state).
  Stop stop;
  stop.signal = interrupted_by;
  stop.stage = stage;
  if (failure) stop.failure = *failure;
  else stop.failure = analysis::Failure{last.step, stage == Master::rotation ? (theta_s + last.rotation) / degree
                                                                                     : last.lift, 0.0,
                                        Interrupted(interrupted_by).what()};
  write_last_state(path.state(), last);   // collective
  stop.checkpointed = true;
  return stop;
}

}  // namespace spatula::app
