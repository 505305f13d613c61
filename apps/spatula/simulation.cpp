#include "simulation.hpp"

#include "checkpoint.hpp"
#include "interruption.hpp"
#include "spectrum_output.hpp"

#include "io/checked_write.hpp"
#include "solvers/out_of_memory.hpp"

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
      : file_(file), young_(young), reference_(reference_energy), initial_internal_(initial_internal_energy),
        initial_contact_(initial_contact_energy)
  {
    if (resume_after >= 0) {
      keep_rows_up_to(file, resume_after);
      written_ = static_cast<std::streamoff>(std::filesystem::file_size(file));
      out_.open(file, std::ios::app);
      io::check_written(out_, file_);
      out_ << std::setprecision(10);
      return;
    }
    out_.open(file);
    out_ << "step,stage,theta_y_deg,u_z_nm,M_y_nNnm,M_y_per_ER0^3,P_z_nN,P_z_per_ER0^2,Pi_int_1e-18J,"
            "Pi_ext_1e-18J,Pi_c_1e-18J,Pi_sa_1e-18J,Pi_ext_per_Pi_c0,Pi_int_per_Pi_c0,Pi_sa_per_Pi_c0,"
            "dissipated_per_Pi_c0,balance_error_per_Pi_c0,after_jump,contact_faces_active,contact_faces_skipped,"
            "newton_iterations,negative_pivots,wall_s,u_x_nm\n";
    commit_row();
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
    commit_row();
  }

private:
  // The rows written so far reach the file, or the curve is cut back to its last whole row (a full disk leaves a
  // readable curve up to the last state that fitted) and the write failure is thrown.
  void commit_row()
  {
    try {
      io::check_written(out_, file_);
      written_ = out_.tellp();   // the end of the file once a row has been written (opened to append)
    } catch (...) {
      std::error_code ignored;
      if (written_ >= 0) std::filesystem::resize_file(file_, static_cast<std::uintmax_t>(written_), ignored);
      throw;
    }
  }

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
    io::write_text_file(file + ".writing", kept);
    io::rename_path(file + ".writing", file);
  }

  std::string file_;
  std::ofstream out_;
  std::streamoff written_ = -1;   // bytes of the curve's whole rows in the file
  double young_, reference_, initial_internal_, initial_contact_;
};

// One run of a scene: the distributed system, its solvers and load path, and everything written along the way
// (curve rows, progress lines, fields, checkpoints). run_simulation calls its phases in order.
class Run {
public:
  Run(const Scene& scene, const geometry::SpatulaShape& shape, const mesh::HexMesh& mesh,
      const mesh::Partition& partition, Teuchos::RCP<const Teuchos::Comm<int>> comm,
      const io::OutputDirectory* directory, io::XdmfOutput* fields, std::ostream& out);

  // On a rough substrate the pad starts pressed onto it (Adhesion/Rough Substrate/conform initially); a failure
  // to find that equilibrium stops the run before any load.
  std::optional<Stop> press_onto_rough_substrate();
  // From the undeformed state, a checkpoint (restart) or a stopped run's last state (resume); opens the curve.
  void start();
  // The rotation, stopping at every checkpoint inclination on the way, then the lift. A signal ends either at a
  // converged state (Interrupted, on every rank together): its number is returned in `interrupted_by`.
  std::optional<analysis::Failure> follow_load_path(int& interrupted_by);
  // Detachment, the solver's counters, and why the run stopped (with its last state checkpointed), if it did.
  std::optional<Stop> finish(std::optional<analysis::Failure> failure, int interrupted_by);

private:
  using Master = discretization::Master;
  using Vector = discretization::Vector;
  using clock = std::chrono::steady_clock;
  static constexpr double balance_limit = 2e-3;   // |Pi_ext - Pi_int - Pi_sa - D| / Pi_c0, the paper's bound

  void on_point(const analysis::LoadPoint& p, const Vector& x);
  void on_descent();
  void print_step(const analysis::LoadPoint& p);
  void checkpoint_if_due(const analysis::LoadPoint& p, const Vector& x);
  void write_fields(const Vector& x, double time);
  RunRecord record_at(const analysis::LoadPoint& p) const;   // what a resumed run needs besides the state at p
  void write_last_state(const Vector& x, const analysis::LoadPoint& p);   // collective
  void write_checkpoint_at(double theta_y);                              // collective
  double load_of(const analysis::LoadPoint& p) const   // theta_y [deg] in the rotation, u_z [nm] in the lift
  {
    return stage_ == Master::rotation ? (theta_s_ + p.rotation) / degree : p.lift;
  }
  double released_fraction(const analysis::LoadPoint& p) const
  {
    return 2.0 * (p.contact_energy - initial_contact_) / reference_energy_;
  }
  bool detached(const analysis::LoadPoint& p);
  std::string checkpoint_file() const { return directory_ ? directory_->file("checkpoints.h5") : ""; }

  const Scene& scene_;
  const mesh::HexMesh& mesh_;
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  const bool root_;
  const io::OutputDirectory* directory_;
  io::XdmfOutput* fields_;
  std::ostream& out_;
  discretization::SystemOptions options_;
  Teuchos::RCP<discretization::DiscreteSystem> system_;
  solvers::LinearSolverFactory linear_;
  Teuchos::RCP<solvers::SpatulaModel> model_;
  solvers::NewtonSolver newton_;
  analysis::LoadPath path_;
  const double theta_s_, young_;
  double reference_energy_ = 1.0;   // Pi_c0 = A_c w_adh of the full spatula (1 without adhesion)
  std::unique_ptr<CurveWriter> curve_;
  std::unique_ptr<SpectrumOutput> spectrum_;   // Output/tangent spectrum
  Master stage_ = Master::rotation;
  PathStage path_stage_;   // where the path is: rotation, or lift from where
  Teuchos::RCP<Vector> anchors_;   // the state the stiction anchors were set at ('restart state'), kept in checkpoints
  // The energies the curve counts from (the undeformed spatula, or the pad pressed onto a rough substrate) and the
  // peaks the detachment test compares with: kept in every checkpoint, so that a resumed run goes on with them.
  double initial_contact_ = 0.0, initial_internal_ = 0.0;
  double peak_moment_ = 0.0, peak_force_ = 0.0;
  clock::time_point last_checkpoint_ = clock::now();
  bool balance_warned_ = false;
  bool out_of_memory_ = false;   // the load path stopped because an allocation failed (not a detachment)
};

discretization::SystemOptions system_options(const Scene& scene)
{
  discretization::SystemOptions options;
  options.enrichment = enrichment_of(scene);
  if (scene.adhesion.enabled) options.contact = contact::make_contact_model(scene.adhesion.settings);
  return options;
}

Teuchos::RCP<discretization::DiscreteSystem> make_system(const Scene& scene, const geometry::SpatulaShape& shape,
                                                         const mesh::HexMesh& mesh, const mesh::Partition& partition,
                                                         Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                                         const discretization::SystemOptions& options)
{
  const auto p1 = shape.point(1);
  const auto constraints =
      discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, scene.loading.hold_contact_surface);
  return Teuchos::rcp(new discretization::DiscreteSystem(mesh, partition, constraints, scene.material, comm, options));
}

Run::Run(const Scene& scene, const geometry::SpatulaShape& shape, const mesh::HexMesh& mesh,
         const mesh::Partition& partition, Teuchos::RCP<const Teuchos::Comm<int>> comm,
         const io::OutputDirectory* directory, io::XdmfOutput* fields, std::ostream& out)
    : scene_(scene), mesh_(mesh), comm_(comm), root_(comm->getRank() == 0), directory_(directory), fields_(fields),
      out_(out), options_(system_options(scene)), system_(make_system(scene, shape, mesh, partition, comm, options_)),
      linear_(scene.linear_solver, scene.linear_solver.type == solvers::LinearSolverType::gmres_amg
                                       ? std::make_shared<const discretization::NodeBlocks>(system_->node_blocks())
                                       : nullptr),
      model_(Teuchos::rcp(new solvers::SpatulaModel(system_, linear_.lows_factory()))),
      newton_(model_, scene.newton, linear_),
      path_(*model_, newton_, root_ ? &out : nullptr, scene.output.convergence_tables), theta_s_(shape.theta_s()),
      young_(scene.material.young), initial_contact_(path_.last().contact_energy)
{
  if (scene.loading.past_instabilities == analysis::LoadPath::PastFolds::arc_length)
    path_.enable_arc_length(scene.loading.arc_length_steps);
  else
    path_.set_past_folds(scene.loading.past_instabilities);
  const auto& contact = options_.contact;
  if (contact) reference_energy_ = 2.0 * system_->contact_area() * contact->work_of_adhesion();
  if (root_ && contact)
    out << "adhesion: " << contact->description() << "\n"
        << "  contact area A_c = " << 2.0 * system_->contact_area() << " nm^2, Pi_c0 = A_c w_adh = "
        << reference_energy_ << " nN nm = " << reference_energy_ / young_ << " E R0^3\n";
  auto jump = scene.loading.jump;   // the step balance check in the half model's energy (adhesion only)
  jump.step_balance_tolerance = contact ? scene.loading.step_balance_tolerance * reference_energy_ / 2.0 : 0.0;
  path_.set_jump_parameters(jump);
  if (contact) path_.set_detachment_test([this](const analysis::LoadPoint& p) { return detached(p); });
  path_.set_descent_watch([this] { on_descent(); });
}

// Detachment ends a path cleanly: the moment (rotation) or the pull (lift) has collapsed to under 1 % of its peak
// with most of the pad released.
bool Run::detached(const analysis::LoadPoint& p)
{
  peak_moment_ = std::max(peak_moment_, p.moment);
  peak_force_ = std::max(peak_force_, p.force);
  const bool collapsed = stage_ == Master::rotation ? p.moment < 0.01 * peak_moment_ : p.force < 0.01 * peak_force_;
  return collapsed && released_fraction(p) > 0.5;
}

void Run::write_fields(const Vector& x, double time)
{
  io::FieldState state;
  state.time = time;
  state.displacement = system_->node_displacements(x);
  auto trace = system_->element_cauchy_trace(x);
  for (auto& value : trace) value /= young_;
  state.cell_scalars["I1"] = std::move(trace);   // the paper's colour scale: tr(sigma) / E
  if (fields_) fields_->add_state(state);
}

RunRecord Run::record_at(const analysis::LoadPoint& p) const
{
  return {initial_internal_, initial_contact_, peak_moment_, peak_force_, p.seconds,
          fields_ ? fields_->state_count() : 0, p.step_control};
}

void Run::write_last_state(const Vector& x, const analysis::LoadPoint& p)
{
  auto record = record_at(p);
  const auto* jump = path_.jump_in_progress();
  if (jump) record.seconds = path_.elapsed_seconds();   // the descent's time so far counts too
  write_checkpoint(checkpoint_file(), last_state_label, *system_, x, p, path_stage_, scene_, record, anchors_.get(),
                   jump);
  note_checkpoint_written();
}

void Run::write_checkpoint_at(double theta_y)
{
  write_checkpoint(checkpoint_file(), checkpoint_label(theta_y), *system_, path_.state(), path_.last(), path_stage_,
                   scene_, record_at(path_.last()), anchors_.get());
  if (root_) out_ << "checkpoint " << checkpoint_label(theta_y) << " written\n";
}

void Run::print_step(const analysis::LoadPoint& p)
{
  const std::ios_base::fmtflags flags = out_.flags();
  const std::streamsize precision = out_.precision();
  out_ << "step " << std::setw(4) << p.step << "  " << stage_name(stage_) << "  theta_y " << std::fixed
       << std::setprecision(3) << std::setw(8) << (theta_s_ + p.rotation) / degree << " deg  u_z " << std::setw(9)
       << p.lift << " nm  M_y " << std::setprecision(4) << std::setw(10) << 2 * p.moment << " nN nm  P_z "
       << std::setw(9) << 2 * p.force << " nN  Pi_int " << std::setw(9) << curve_->internal(p);
  if (options_.contact)
    out_ << "  Pi_sa/Pi_c0 " << std::setprecision(4) << curve_->stored_adhesion(p) / reference_energy_
         << "  balance " << std::scientific << std::setprecision(1) << curve_->balance_error(p) << std::fixed
         << "  faces " << p.active_faces << "+" << p.skipped_faces;
  out_ << "  newton " << p.newton_iterations << "  neg.piv " << p.negative_pivots << "  " << std::setprecision(1)
       << p.seconds << " s" << std::endl;
  out_.flags(flags);   // the step line's format stays with it
  out_.precision(precision);
  // A curve whose energies do not balance is not to be trusted: say so once, when it first happens.
  if (options_.contact && !balance_warned_ && curve_->balance_error(p) > balance_limit) {
    balance_warned_ = true;
    out_ << "warning: at step " << p.step << " the energy balance error " << curve_->balance_error(p)
         << " Pi_c0 exceeds " << balance_limit << " (the paper's bound): the curve from here on is not reliable "
         << "(contact under-resolved? use Q1C2, more contact quadrature points or smaller steps)" << std::endl;
  }
}

// Every 'Output/checkpoint interval' minutes of wall time, the state to resume from if the run is killed (rank 0's
// clock decides for all).
void Run::checkpoint_if_due(const analysis::LoadPoint& p, const Vector& x)
{
  if (scene_.output.checkpoint_minutes <= 0.0) return;
  const std::chrono::duration<double> interval(60.0 * scene_.output.checkpoint_minutes);
  int due = root_ && clock::now() - last_checkpoint_ > interval;
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(due));
  if (!due) return;
  write_last_state(x, p);
  last_checkpoint_ = clock::now();
  if (!root_) return;
  out_ << "checkpoint '" << last_state_label << "' written at step " << p.step;
  if (const auto* jump = path_.jump_in_progress())
    out_ << ", with the jump's energy descent at iteration " << jump->iterations;
  out_ << std::endl;
}

void Run::on_point(const analysis::LoadPoint& p, const Vector& x)
{
  if (root_) {
    curve_->write(p, stage_name(stage_), theta_s_);
    print_step(p);
  }
  if (scene_.output.tangent_spectrum > 0) {
    if (!spectrum_)
      spectrum_ = std::make_unique<SpectrumOutput>(*system_, scene_.linear_solver.mumps, scene_.output.tangent_spectrum,
                                                   root_ && directory_ ? directory_->file("spectrum.csv") : "");
    spectrum_->write(p, stage_name(stage_), load_of(p), x);
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
  system_->set_displacements(*guess, u);
  const auto failure =
      path_.equilibrate(*guess, analysis::LoadPath::spatula_control(Master::rotation, scene_.loading.free_lift));
  if (failure) {   // before any load: the stage is the rotation's start, the reason says what failed
    auto pressing = *failure;
    pressing.reason = "pressing the pad onto the rough substrate: " + pressing.reason;
    return Stop{pressing, 0, false, Master::rotation};
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
    if (path_stage_.lifting) stage_ = Master::lift;
    if (root_)
      out_ << "restart from '" << restart_label(loading) << "' of " << loading.restart_file << " (step "
           << history.step << ", u_z " << history.lift << " nm" << (path_stage_.lifting ? ", in the lift" : "") << ")"
           << (anchor ? "; stiction anchors set at this state" : "") << "\n";
    if (auto jump = read_jump_in_progress(scene_, *system_)) {
      if (root_)
        out_ << "  it was inside a jump past an instability (" << stage_name(jump->controlled) << " = "
             << (jump->controlled == Master::rotation ? (theta_s_ + jump->value) / degree : jump->value)
             << ", energy descent at iteration " << jump->iterations << ")\n";
      path_.resume_jump(std::move(*jump));
    }
  }
  if (root_)
    curve_ = std::make_unique<CurveWriter>(directory_->file("curve.csv"), young_, reference_energy_,
                                           initial_internal_, initial_contact_, scene_.resume ? path_.last().step : -1);
  if (!scene_.resume) {   // a resumed run has its starting state in its curve and fields already
    if (root_) curve_->write(path_.last(), stage_name(stage_), theta_s_);
    write_fields(path_.state(), (theta_s_ + path_.last().rotation) / degree);
  }
}

std::optional<analysis::Failure> Run::follow_load_path(int& interrupted_by)
{
  using analysis::LoadPath;
  const auto& loading = scene_.loading;
  const auto on_point = [this](const analysis::LoadPoint& p, const Vector& x) { this->on_point(p, x); };
  std::optional<analysis::Failure> failure;
  try {
    std::vector<double> stops;
    const double current = (theta_s_ + path_.last().rotation) / degree;
    for (double c : loading.checkpoints)
      if (c > current + 1e-9 && c < loading.theta_y - 1e-9) stops.push_back(c);
    if (!path_stage_.lifting) stops.push_back(loading.theta_y);
    for (double stop : stops) {
      failure = path_.advance(Master::rotation, stop * degree - theta_s_,
                              LoadPath::spatula_control(Master::rotation, loading.free_lift), loading.rotation_steps,
                              degree, on_point);
      if (failure || path_.detached()) return failure;
      if (std::find(loading.checkpoints.begin(), loading.checkpoints.end(), stop) != loading.checkpoints.end())
        write_checkpoint_at(stop);
    }
    if (loading.type == LoadingType::lift) {
      stage_ = Master::lift;
      if (!path_stage_.lifting) path_stage_ = PathStage{true, path_.last().lift};
      const double target = loading.final_lift + (loading.lift_relative ? path_stage_.lift_start : 0.0);
      auto control = LoadPath::spatula_control(Master::lift, false);
      control.prescribed[static_cast<int>(Master::slide)] = !loading.free_slide;
      failure = path_.advance(Master::lift, target, control, loading.lift_steps, 1.0, on_point);
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

std::optional<Stop> Run::finish(std::optional<analysis::Failure> failure, int interrupted_by)
{
  // No equilibrium beyond a state where most of the pad has let go: that is the detachment.
  if (!interrupted_by && failure && !out_of_memory_ && options_.contact && released_fraction(path_.last()) > 0.5) {
    if (root_)
      out_ << "detachment: no equilibrium beyond " << stage_name(stage_) << " = " << failure->load << " ("
           << failure->reason << ")\n";
    failure.reset();
  } else if (path_.detached() && root_) {
    out_ << "detachment: the " << (stage_ == Master::rotation ? "moment" : "pull") << " has collapsed\n";
  }
  const auto& last = path_.last();
  if (scene_.output.field_interval == 0 || last.step % scene_.output.field_interval != 0)
    write_fields(path_.state(), load_of(last));
  if (root_) {
    const auto& statistics = linear_.mumps_statistics();
    out_ << "solver: " << model_->counters().jacobians << " tangents, " << model_->counters().residuals
         << " residual-only evaluations, " << model_->counters().inadmissible << " inadmissible trial states";
    if (statistics.factorizations > 0)
      out_ << "; MUMPS: " << statistics.analyses << " analyses, " << statistics.factorizations << " factorizations ("
           << statistics.reused << " tangents served by an earlier one, " << statistics.factorization_seconds
           << " s), " << statistics.solves << " solves";
    const auto& multigrid = linear_.multigrid_statistics();
    if (multigrid.setups > 0)
      out_ << "; AMG: " << multigrid.setups << (multigrid.setups == 1 ? " hierarchy, " : " hierarchies, ")
           << multigrid.reuses << " reused, " << multigrid.applications << " applications"
           << (multigrid.fell_back ? ", then MUMPS after a stalled solve" : "");
    if (const auto* descents = path_.descent_statistics())
      out_ << "; jumps' energy descents: " << descents->analyses << " analyses, " << descents->factorizations
           << " factorizations (" << descents->factorization_seconds << " s), " << descents->solves << " solves ("
           << descents->reused << " with kept factors)";
    out_ << "\n";
  }
  if (!failure && !interrupted_by) return std::nullopt;
  // The last converged state, to go on from (spatula --resume, or Loading/restart from = last state).
  Stop stop;
  stop.signal = interrupted_by;
  stop.stage = stage_;
  if (failure && !out_of_memory_ && path_.jump_in_progress())   // a descent stopped at its iteration limit
    failure->reason += "; the descent's state is checkpointed with the last state: a restart from it ('Loading/restart "
                       "from' = 'last state') with a larger 'Loading/Jump/maximum iterations' goes on from there";
  if (failure) stop.failure = *failure;
  else stop.failure = analysis::Failure{last.step, load_of(last), 0.0, Interrupted(interrupted_by).what()};
  write_last_state(path_.state(), last);   // collective
  stop.checkpointed = true;
  return stop;
}

}  // namespace

const char* stage_name(discretization::Master stage)
{
  return stage == discretization::Master::rotation ? "rotation" : stage == discretization::Master::lift ? "lift" : "slide";
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
