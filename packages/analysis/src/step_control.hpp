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
struct StepControllerState {
  double increment = 0.0;
  double failed_load = 0.0;
  bool failed_known = false, bisecting = false;
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
