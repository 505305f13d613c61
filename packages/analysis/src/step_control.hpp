#pragma once
// The step controller of the load path: the increments and the predictor (StepParameters, PredictorWeights) and the
// failed load ahead that bisection approaches (FailedLoad), with what of it a checkpoint keeps.
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

namespace spatula::analysis {

struct StepParameters {
  // The trial state of a step: extrapolated from the last two converged states (secant, first order) or the last
  // three (quadratic: Lagrange polynomial in the load, second order), each from converged states only; a retry
  // after a failed attempt extrapolates them to its shorter increment unless predict_after_failure is false.
  enum class Predictor { secant, quadratic };
  static const std::vector<std::string>& predictor_names();

  double initial = 1.0, minimum = 1e-3, maximum = 5.0;   // increments, in the load's unit (deg or nm)
  int easy_iterations = 4;    // grow the increment after a step that needed at most this many iterations
  double growth = 1.5;
  double cut = 0.5;
  Predictor predictor = Predictor::quadratic;
  bool predict_after_failure = true;
  double curve_tolerance = 0.0;   // CurveResolution's; 0: the increments follow Newton's iterations alone

  static void declare(Teuchos::ParameterList& list, const StepParameters& defaults);
  static StepParameters from(const Teuchos::ParameterList& list, const std::string& path);
};

// The predictor's weights of the current, previous and older converged states (trial = sum of weight x state) for
// a step of `increment` after steps of `previous_increment` and `older_increment` (0: that state is not there).
// Exact for a path linear (secant) or quadratic (quadratic) in the load; the current state alone without history.
struct PredictorWeights {
  double current = 1.0, previous = 0.0, older = 0.0;
};
PredictorWeights predictor_weights(StepParameters::Predictor predictor, double increment, double previous_increment,
                                   double older_increment);

// The nearest load ahead of the converged state where a step failed (Newton did not converge, or converged across
// a snap). A load that fails again from a nearer state (or a load beyond it fails) is, in all likelihood, past a
// limit point: from then on the increments bisect the gap to it instead of trying it from every nearer state, each
// retry a whole failed Newton attempt. Once half the gap would be below the smallest increment, the load itself is
// tried once more: it converges (Newton had only been too far away) or the instability is there. Loads and
// increments in one unit; direction +1 or -1 (the sense of travel).
// What the step controller knows at a converged state, so that a resumed run goes on as the uninterrupted one
// would: the increment it tries next and the failed load ahead (internal units; increment 0: the initial one).
// The last converged states of a smooth stretch of the path (load, reaction; the newest last) and the largest
// |reaction| of the stage so far: what CurveResolution limits the increment by.
struct CurveSamples {
  double load[3] = {0.0, 0.0, 0.0}, reaction[3] = {0.0, 0.0, 0.0};
  int count = 0;      // 0 to 3
  int step = -1;      // the step number of the newest
  double largest = 0.0;
};

struct StepControllerState {
  double increment = 0.0;
  double failed_load = 0.0;
  bool failed_known = false, bisecting = false;
  CurveSamples curve;
};

// Resolving the reaction curve (M_y or P_z against the load): with a tolerance tol > 0 the increment h is at most
// sqrt(8 tol R_max / |R''|), R'' the second divided difference of the last three converged states of the smooth
// stretch and R_max the largest |reaction| of the stage, so that the curve between samples departs from its chord by
// at most tol R_max, and a sampled peak lies within tol R_max of the curve's (|R''| h^2 / 8 for a parabola). Easy
// stretches then take long increments and the top of a pull-off short ones. A jump starts a new stretch. The bound
// never goes below a floor (the stage's initial increment): where the curve is rough at the scale of the
// increments (a peel front's micro-snaps), the second difference grows as the spacing shrinks and would otherwise
// drive the increments down to nothing.
class CurveResolution {
public:
  void start(double tolerance, double floor);   // a stage begins: a new stretch, the largest reaction forgotten
  // The converged state numbered `step`: on the stretch if the newest sample is the state before it (`before`, the
  // step number of the path's last point) and the step was no jump, else the first of a new stretch.
  void reached(int step, int before, bool jumped, double load, double reaction);
  double limit(double increment) const;            // at least the floor (or `increment`, if smaller)
  void save(StepControllerState& state) const { state.curve = samples_; }
  void restore(const StepControllerState& state) { samples_ = state.curve; }

private:
  double tolerance_ = 0.0, floor_ = 0.0;
  CurveSamples samples_;
};

class FailedLoad {
public:
  FailedLoad(double direction, double smallest, double cut);
  void failed(double load);     // a step to `load` failed
  void reached(double value);   // a step converged at `value`: the failed load is forgotten once reached
  void forget();                // after a jump or arc-length past the instability
  bool known() const { return known_; }   // a load ahead failed (a fold may be near)
  // The increment to take from `value`: `increment`, or while bisecting half the gap to the failed load (the whole
  // gap once its half would be below the smallest increment).
  double limit(double increment, double value) const;
  void save(StepControllerState& state) const;
  void restore(const StepControllerState& state);

private:
  static double tolerance(double value);
  double direction_, smallest_, cut_;
  double load_ = 0.0;
  bool known_ = false, bisecting_ = false;
};

}  // namespace spatula::analysis
