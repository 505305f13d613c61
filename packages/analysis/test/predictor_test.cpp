// The step predictor's weights: the secant is exact on a path linear in the load, the quadratic on one quadratic in
// it (unequal increments), and without the history they need both fall back (quadratic -> secant -> current state).
#include "analysis/load_stepping.hpp"

#include <gtest/gtest.h>

using spatula::analysis::PredictorWeights;
using spatula::analysis::predictor_weights;
using Predictor = spatula::analysis::StepParameters::Predictor;

namespace {

// The predicted value of path(load) at load 0 + t from states at -h1 - h2, -h2 and 0.
template <class Path>
double predicted(const PredictorWeights& w, Path path, double h1, double h2)
{
  return w.current * path(0.0) + w.previous * path(-h2) + w.older * path(-h1 - h2);
}

TEST(Predictor, SecantIsExactOnALinearPath)
{
  const auto line = [](double load) { return 3.0 - 2.5 * load; };
  const auto w = predictor_weights(Predictor::secant, 0.7, 0.4, 0.9);
  EXPECT_DOUBLE_EQ(w.older, 0.0);
  EXPECT_NEAR(predicted(w, line, 0.9, 0.4), line(0.7), 1e-13);
}

TEST(Predictor, QuadraticIsExactOnAQuadraticPathWithUnequalIncrements)
{
  const auto parabola = [](double load) { return 1.5 + 0.3 * load - 4.0 * load * load; };
  for (const double t : {0.1, 0.4, 1.3}) {
    const auto w = predictor_weights(Predictor::quadratic, t, 0.4, 0.9);
    EXPECT_NEAR(w.current + w.previous + w.older, 1.0, 1e-13);   // a constant path stays put
    EXPECT_NEAR(predicted(w, parabola, 0.9, 0.4), parabola(t), 1e-12) << "increment " << t;
  }
  // The secant is not: its error is the curvature times t (t + h2).
  const auto secant = predictor_weights(Predictor::secant, 0.4, 0.4, 0.9);
  EXPECT_NEAR(predicted(secant, parabola, 0.9, 0.4) - parabola(0.4), 4.0 * 0.4 * 0.8, 1e-12);
}

TEST(Predictor, WithoutHistoryTheQuadraticFallsBackToTheSecantThenToTheCurrentState)
{
  const auto secant = predictor_weights(Predictor::secant, 0.5, 0.25, 0.0);
  const auto quadratic_without_older = predictor_weights(Predictor::quadratic, 0.5, 0.25, 0.0);
  EXPECT_DOUBLE_EQ(quadratic_without_older.current, secant.current);
  EXPECT_DOUBLE_EQ(quadratic_without_older.previous, secant.previous);
  EXPECT_DOUBLE_EQ(secant.current, 3.0);
  const auto none = predictor_weights(Predictor::quadratic, 0.5, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(none.current, 1.0);
  EXPECT_DOUBLE_EQ(none.previous, 0.0);
  EXPECT_DOUBLE_EQ(none.older, 0.0);
}

}  // namespace
