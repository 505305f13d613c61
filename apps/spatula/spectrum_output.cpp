#include "spectrum_output.hpp"

#include "io/checked_write.hpp"

#include <iomanip>

namespace spatula::app {

SpectrumOutput::SpectrumOutput(discretization::DiscreteSystem& system, const solvers::MumpsParameters& mumps,
                               int iterations, const std::string& file)
    : system_(system), iterations_(iterations), file_(file)
{
  // Exact LDL^T factors: the inertia and the smallest eigenvalues need them.
  solver_ = std::make_unique<solvers::MumpsSolver>(system.owned_map(), mumps.exact_ldlt());
  if (file_.empty()) return;
  out_.open(file_);
  out_ << "step,stage,load,newton_iterations,nearest_eigenvalue_nN_per_nm,nearest_over_mean_diagonal,"
          "participation,negative_pivots,rayleigh_residual\n"
       << std::setprecision(10);
  io::check_written(out_, file_);
}

void SpectrumOutput::write(const analysis::LoadPoint& point, const char* stage, double load,
                           const discretization::Vector& x)
{
  system_.evaluate(x, nullptr, true);
  const auto eigenvalue =
      analysis::nearest_eigenvalue(*system_.jacobian(), *solver_, iterations_, system_.mean_diagonal());
  if (file_.empty()) return;
  out_ << point.step << "," << stage << "," << load << "," << point.newton_iterations << "," << eigenvalue.value
       << "," << eigenvalue.relative << "," << eigenvalue.participation << "," << eigenvalue.negative_pivots << ","
       << eigenvalue.residual << "\n";
  io::check_written(out_, file_);
}

}  // namespace spatula::app
