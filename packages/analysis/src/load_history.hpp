#pragma once
// The record of a load path: its converged points (LoadPoint), numbered on from a restart's, with the work of the
// reactions along the path (trapezoidal rule), the energy released in its jumps, and the wall clock; what a
// checkpoint keeps of the path and a restart carries on.
#include "analysis/step_control.hpp"
#include "discretization/discrete_system.hpp"

#include <vector>

namespace spatula::analysis {

// One converged state on the load path (half-model values: the app doubles them for the full spatula).
struct LoadPoint {
  int step = 0;
  double rotation = 0.0;     // alpha [rad] (theta_y = theta_s + alpha)
  double lift = 0.0;         // w [nm], the face centre's displacement along the lift direction (spatula: u_z)
  double slide = 0.0;        // s [nm], along the slide direction (spatula: X, held at 0)
  double moment = 0.0;       // M_y on the face [nN nm]
  double force = 0.0;        // force on the face along the lift direction (spatula: P_z) [nN]
  double slide_force = 0.0;  // force on the face along the slide direction [nN]
  double internal_energy = 0.0;   // Pi_int [nN nm]
  double contact_energy = 0.0;    // Pi_c [nN nm]
  int active_faces = 0, skipped_faces = 0;   // contact faces integrated / beyond the cut-off
  double external_work = 0.0;     // int M dalpha + int P dw along the path [nN nm]
  int newton_iterations = 0;
  int negative_pivots = -1;
  double seconds = 0.0;      // wall time since the run began
  bool after_jump = false;   // the first state on the far side of an instability
  double released = 0.0;     // energy released in that jump (Pi_int + Pi_c before minus after, at fixed load) [nN nm]
  double dissipated = 0.0;   // energy released in all jumps so far [nN nm]
  double sliding = 0.0;      // energy dissipated by contact friction up to this state [nN nm] (a law with state)
  StepControllerState step_control;   // the controller's state after this point (a resumed run's start)

  // The reaction conjugate to a master: the moment, the force along the lift or along the slide.
  double reaction(discretization::Master master) const
  {
    return master == discretization::Master::rotation ? moment : master == discretization::Master::lift ? force
                                                                                                        : slide_force;
  }
};

// The first state on the far side of an instability that released `released` [nN nm, half model].
void mark_jump(LoadPoint& point, double released);

class LoadHistory {
public:
  LoadHistory();

  // The point of a converged state x of `system` (masters, reactions, energies, the solve's counts), numbered next,
  // its work of the reactions and dissipation carried on from the last point.
  LoadPoint measure(discretization::DiscreteSystem& system, const discretization::Vector& x, int iterations,
                    int negative_pivots) const;
  void append(const LoadPoint& point) { points_.push_back(point); }
  // The work of the reactions minus the change of Pi_int + Pi_c from the last point to `point`: near zero on a
  // smooth path, the energy released where the state crossed a snap.
  double released_energy(const LoadPoint& point) const;
  void mark_last_as_jump(double released) { mark_jump(points_.back(), released); }

  // Starts again from `point`, the measure of a restart's state, with what `carried` says of the path before it:
  // its step number, work of the reactions and dissipation, and when positive its wall time (the clock goes on).
  void restart(LoadPoint point, const LoadPoint& carried);

  const LoadPoint& last() const { return points_.back(); }
  const std::vector<LoadPoint>& points() const { return points_; }
  int next_step() const { return step_offset_ + static_cast<int>(points_.size()); }
  double elapsed_seconds() const;   // wall time since the path began (a resumed run's included)

private:
  std::vector<LoadPoint> points_;
  int step_offset_ = 0;   // the step number of the first point (a restart's)
  double started_ = 0.0;
};

}  // namespace spatula::analysis
