// The step controller's parts: the increments' parameters, the predictor's weights and the failed load ahead.
#include "analysis/step_control.hpp"

#include "parameters/parameter_validation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace spatula::analysis {

FailedLoad::FailedLoad(double direction, double smallest, double cut)
  : direction_(direction), smallest_(smallest), cut_(cut)
{
}

void FailedLoad::failed(double load)
{
  if (known_ && direction_ * (load - load_) >= -tolerance(load)) {
    bisecting_ = true;   // the same load (or one beyond it) failed again
  } else {
    load_ = load;
    known_ = true;
  }
}

void FailedLoad::reached(double value)
{
  if (known_ && direction_ * (load_ - value) <= tolerance(value)) forget();
}

void FailedLoad::forget()
{
  known_ = bisecting_ = false;
}

double FailedLoad::limit(double increment, double value) const
{
  if (!bisecting_) return increment;
  const double gap = direction_ * (load_ - value);
  return gap * cut_ >= smallest_ * (1 - 1e-12) ? std::min(increment, gap * cut_) : gap;
}

void FailedLoad::save(StepControllerState& state) const
{
  state.failed_load = load_;
  state.failed_known = known_;
  state.bisecting = bisecting_;
}

void FailedLoad::restore(const StepControllerState& state)
{
  load_ = state.failed_load;
  known_ = state.failed_known;
  bisecting_ = state.bisecting;
}

double FailedLoad::tolerance(double value)
{
  return 1e-12 * std::max(1.0, std::abs(value));
}

void CurveResolution::start(double tolerance, double floor)
{
  tolerance_ = tolerance;
  floor_ = floor;
  samples_ = CurveSamples{};
}

void CurveResolution::reached(int step, int before, bool jumped, double load, double reaction)
{
  auto& s = samples_;
  if (jumped || s.step != before) s.count = 0;
  s.step = step;
  if (s.count == 3) {
    for (int k = 0; k < 2; ++k) {
      s.load[k] = s.load[k + 1];
      s.reaction[k] = s.reaction[k + 1];
    }
    s.count = 2;
  }
  s.load[s.count] = load;
  s.reaction[s.count] = reaction;
  ++s.count;
  s.largest = std::max(s.largest, std::abs(reaction));
}

double CurveResolution::limit(double increment) const
{
  const auto& s = samples_;
  if (tolerance_ <= 0.0 || s.count < 3) return increment;
  const double h1 = s.load[1] - s.load[0], h2 = s.load[2] - s.load[1];
  if (h1 == 0.0 || h2 == 0.0) return increment;
  const double second = 2.0 * ((s.reaction[2] - s.reaction[1]) / h2 - (s.reaction[1] - s.reaction[0]) / h1) /
                        (h1 + h2);
  if (second == 0.0) return increment;
  const double resolved = std::sqrt(8.0 * tolerance_ * s.largest / std::abs(second));
  return std::min(increment, std::max(resolved, floor_));
}

const std::vector<std::string>& StepParameters::predictor_names()
{
  static const std::vector<std::string> names = {"secant", "quadratic"};
  return names;
}

void StepParameters::declare(Teuchos::ParameterList& list, const StepParameters& d)
{
  using parameters::Range;
  parameters::declare_double(list, "initial", d.initial, "first increment", Range::positive());
  parameters::declare_double(list, "minimum", d.minimum, "smallest increment before giving up", Range::positive());
  parameters::declare_double(list, "maximum", d.maximum, "largest increment", Range::positive());
  parameters::declare_int(list, "easy iterations", d.easy_iterations, "grow the increment after steps with at most "
                          "this many Newton iterations", Range::closed(1, 100));
  parameters::declare_double(list, "growth", d.growth, "increment growth factor", {1.0, 10.0, false, false});
  parameters::declare_double(list, "cut", d.cut, "increment factor after a failed step", {0.0, 1.0, true, true});
  parameters::declare_string(list, "predictor", parameters::name_of(d.predictor, predictor_names()),
                             "the trial state of a step: extrapolated from the last two converged states (secant) or "
                             "the last three (quadratic in the load)", predictor_names());
  parameters::declare_bool(list, "predict after a failure", d.predict_after_failure,
                           "a retry with a shorter increment after a failed attempt starts from the predictor "
                           "(true) or from the last converged state with only the load moved (false)");
  parameters::declare_double(list, "curve tolerance", d.curve_tolerance,
                             "0: off. Else the increment is also at most sqrt(8 tol R_max / |R''|) (but not below "
                             "'initial'), R'' the reaction curve's second difference over the last three converged "
                             "states, R_max the stage's largest reaction: the curve, and a peak of it, sampled within "
                             "tol R_max",
                             {0.0, 1.0, false, true});
}

StepParameters StepParameters::from(const Teuchos::ParameterList& list, const std::string& path)
{
  StepParameters p;
  p.initial = list.get<double>("initial");
  p.minimum = list.get<double>("minimum");
  p.maximum = list.get<double>("maximum");
  p.easy_iterations = list.get<int>("easy iterations");
  p.growth = list.get<double>("growth");
  p.cut = list.get<double>("cut");
  p.predictor = parameters::choice<Predictor>(list, "predictor", predictor_names());
  p.predict_after_failure = list.get<bool>("predict after a failure");
  p.curve_tolerance = list.get<double>("curve tolerance");
  if (p.minimum > p.initial)
    parameters::fail(parameters::key_path(path, "minimum"), p.minimum, "must not exceed 'initial' = " + std::to_string(p.initial));
  if (p.maximum < p.initial)
    parameters::fail(parameters::key_path(path, "maximum"), p.maximum, "must not be below 'initial' = " + std::to_string(p.initial));
  return p;
}

PredictorWeights predictor_weights(StepParameters::Predictor predictor, double increment, double previous_increment,
                                   double older_increment)
{
  const double t = increment, h2 = previous_increment, h1 = older_increment;
  PredictorWeights w;
  if (predictor == StepParameters::Predictor::quadratic && h2 > 0.0 && h1 > 0.0) {
    // The Lagrange polynomial through (-h1 - h2, older), (-h2, previous), (0, current) at t, in Newton's form:
    // current + (t + c) (current - previous) / h2 - c (previous - older) / h1,  c = t (t + h2) / (h1 + h2).
    const double c = t * (t + h2) / (h1 + h2);
    w = {1.0 + (t + c) / h2, -(t + c) / h2 - c / h1, c / h1};
  } else if (h2 > 0.0) {   // secant: current + t (current - previous) / h2
    w = {1.0 + t / h2, -t / h2, 0.0};
  }
  return w;
}

}  // namespace spatula::analysis
