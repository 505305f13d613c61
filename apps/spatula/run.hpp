#pragma once
// The app's run of one scene (simulation.cpp): its phases, and the state it keeps between them. Internal to the app:
// run_simulation (simulation.hpp) is its interface.
#include "checkpoint.hpp"
#include "curve_writer.hpp"
#include "simulation.hpp"
#include "spectrum_output.hpp"

#include "solvers/linear_solver.hpp"
#include "solvers/newton.hpp"

#include <chrono>
#include <memory>
#include <optional>

namespace spatula::app {

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
  static constexpr double degree = 3.14159265358979323846 / 180.0;
  static constexpr double balance_limit = 2e-3;   // |Pi_ext - Pi_int - Pi_sa - D| / Pi_c0, the paper's bound

  void on_point(const analysis::LoadPoint& p, const Vector& x);
  void on_descent();
  void print_step(const analysis::LoadPoint& p);
  void checkpoint_if_due(const analysis::LoadPoint& p, const Vector& x);
  void write_fields(const Vector& x, double time);
  RunRecord record_at(const analysis::LoadPoint& p) const;   // what a resumed run needs besides the state at p
  void write_last_state(const Vector& x, const analysis::LoadPoint& p);   // collective
  void write_checkpoint_at(double theta_y);                              // collective
  // The current stage's load: theta_y [deg], u_z or u_x [nm], P_z or P_x [nN, full spatula].
  double load_of(const analysis::LoadPoint& p) const { return load_of(p, stage()); }
  double load_of(const analysis::LoadPoint& p, const Stage& stage) const
  {
    if (!stage.force()) return motion_of(p, stage.master());
    return full_spatula(p.reaction(stage.master()));
  }
  double released_fraction(const analysis::LoadPoint& p) const
  {
    return full_spatula(p.contact_energy - initial_contact_) / reference_energy_;
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
  const Stage& stage() const { return scene_.loading.stages.at(static_cast<std::size_t>(path_stage_.index)); }
  // A motion of the end face at p, in its stage's unit: theta_y [deg], u_z or u_x [nm].
  double motion_of(const analysis::LoadPoint& p, Master motion) const
  {
    return motion == Master::rotation ? (theta_s_ + p.rotation) / degree : motion == Master::lift ? p.lift : p.slide;
  }
  // One stage to its target (a rotation stopping at each checkpoint inclination on the way): a failure, or
  // `detached` set where the spatula let go.
  std::optional<analysis::Failure> follow_stage(const Stage& stage, double target, bool& detached);
  PathStage path_stage_;   // where the path is: which stage, begun where
  double peak_slide_ = 0.0;   // the largest |X force| of a slide stage (not checkpointed)
  Teuchos::RCP<Vector> anchors_;   // the state the stiction anchors were set at ('restart state'), kept in checkpoints
  // The energies the curve counts from (the undeformed spatula, or the pad pressed onto a rough substrate) and the
  // peaks the detachment test compares with: kept in every checkpoint, so that a resumed run goes on with them.
  double initial_contact_ = 0.0, initial_internal_ = 0.0;
  double peak_moment_ = 0.0, peak_force_ = 0.0;
  clock::time_point last_checkpoint_ = clock::now();
  bool balance_warned_ = false;
  std::optional<double> paused_at_;   // --stop-after-checkpoint: the inclination [deg] the run stopped at
  bool paused() const { return paused_at_.has_value(); }
  bool out_of_memory_ = false;   // the load path stopped because an allocation failed (not a detachment)
};

}  // namespace spatula::app
