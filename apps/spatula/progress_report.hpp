#pragma once
// The run's log lines: one per converged state (the progress a user and scripts/run-study.py read), and the solver's
// counters when the path ends.
#include "curve_writer.hpp"

#include "analysis/load_stepping.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/spatula_model.hpp"

#include <ostream>
#include <string>

namespace spatula::app {

// "step N  <stage>  theta_y .. deg  u_z .. nm  M_y ..  P_z ..  Pi_int .." and, with adhesion (`reference_energy`
// Pi_c0 > 0), the stored adhesion energy, the balance error and the contact faces; the stream's format is kept.
void print_state_line(std::ostream& out, const analysis::LoadPoint& p, const std::string& stage, double theta_s,
                      const CurveWriter& curve, double reference_energy);

// "solver: N tangents, ...; MUMPS: ...; AMG: ...; jumps' energy descents: ..." (the parts that were used).
void print_solver_counts(std::ostream& out, const solvers::SpatulaModel& model,
                         const solvers::LinearSolverFactory& linear, const analysis::LoadPath& path);

}  // namespace spatula::app
