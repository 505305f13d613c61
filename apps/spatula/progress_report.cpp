#include "progress_report.hpp"

#include <iomanip>

namespace spatula::app {

namespace {

constexpr double degree = 3.14159265358979323846 / 180.0;

}  // namespace

void print_state_line(std::ostream& out, const analysis::LoadPoint& p, const std::string& stage, double theta_s,
                      const CurveWriter& curve, double reference_energy)
{
  const std::ios_base::fmtflags flags = out.flags();
  const std::streamsize precision = out.precision();
  out << "step " << std::setw(4) << p.step << "  " << stage << "  theta_y " << std::fixed
      << std::setprecision(3) << std::setw(8) << (theta_s + p.rotation) / degree << " deg  u_z " << std::setw(9)
      << curve.u_z(p) << " nm  M_y " << std::setprecision(4) << std::setw(10) << full_spatula(p.moment)
      << " nN nm  P_z " << std::setw(9) << curve.P_z(p) << " nN  Pi_int " << std::setw(9) << curve.internal(p);
  if (reference_energy > 0.0)
    out << "  Pi_sa/Pi_c0 " << std::setprecision(4) << curve.stored_adhesion(p) / reference_energy
        << "  balance " << std::scientific << std::setprecision(1) << curve.balance_error(p) << std::fixed
        << "  faces " << p.active_faces << "+" << p.skipped_faces;
  out << "  newton " << p.newton_iterations << "  neg.piv " << p.negative_pivots << "  " << std::setprecision(1)
      << p.seconds << " s" << std::endl;
  out.flags(flags);   // the step line's format stays with it
  out.precision(precision);
}

void print_solver_counts(std::ostream& out, const solvers::SpatulaModel& model,
                         const solvers::LinearSolverFactory& linear, const analysis::LoadPath& path)
{
  const auto& statistics = linear.mumps_statistics();
  out << "solver: " << model.counters().jacobians << " tangents, " << model.counters().residuals
      << " residual-only evaluations, " << model.counters().inadmissible << " inadmissible trial states";
  if (statistics.factorizations > 0)
    out << "; MUMPS: " << statistics.analyses << " analyses, " << statistics.factorizations << " factorizations ("
        << statistics.reused << " tangents served by an earlier one, " << statistics.factorization_seconds
        << " s), " << statistics.solves << " solves";
  const auto& multigrid = linear.multigrid_statistics();
  if (multigrid.setups > 0)
    out << "; AMG: " << multigrid.setups << (multigrid.setups == 1 ? " hierarchy, " : " hierarchies, ")
        << multigrid.reuses << " reused, " << multigrid.applications << " applications"
        << (multigrid.fell_back ? ", then MUMPS after a stalled solve" : "");
  if (const auto* descents = path.descent_statistics())
    out << "; jumps' energy descents: " << descents->analyses << " analyses, " << descents->factorizations
        << " factorizations (" << descents->factorization_seconds << " s), " << descents->solves << " solves ("
        << descents->reused << " with kept factors)";
  out << "\n";
}

}  // namespace spatula::app
