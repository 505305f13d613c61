#pragma once
// Output/tangent spectrum: at every converged state, the tangent's eigenvalue nearest zero and how localized its
// mode is (analysis::nearest_eigenvalue), into spectrum.csv beside the curve. A diagnosis of how close the path
// runs to a limit point (slow Newton convergence at a moving peel front); it costs one factorization per state.
#include "analysis/load_stepping.hpp"
#include "analysis/tangent_spectrum.hpp"
#include "discretization/discrete_system.hpp"

#include <fstream>
#include <memory>
#include <string>

namespace spatula::app {

class SpectrumOutput {
public:
  // `file`: written by rank 0 (empty on the others); `iterations`: inverse iterations per state.
  SpectrumOutput(discretization::DiscreteSystem& system, const solvers::MumpsParameters& mumps, int iterations,
                 const std::string& file);
  // Collective: assembles the tangent at the converged x, factors it and writes a row.
  void write(const analysis::LoadPoint& point, const char* stage, double load, const discretization::Vector& x);

private:
  discretization::DiscreteSystem& system_;
  std::unique_ptr<solvers::MumpsSolver> solver_;
  int iterations_;
  std::string file_;
  std::ofstream out_;
};

}  // namespace spatula::app
