#include "solvers/convergence_table.hpp"

#include "solvers/front_diagnosis.hpp"

#include <NOX_Abstract_Group.H>
#include <NOX_Solver_Generic.H>
#include <NOX_Solver_LineSearchBased.H>
#include <NOX_Thyra_Vector.H>
#include <Thyra_TpetraThyraWrappers.hpp>

#include <chrono>
#include <iomanip>
#include <ostream>

namespace spatula::solvers {

namespace {

using Extract = Thyra::TpetraOperatorVectorExtraction<double, discretization::LocalOrdinal,
                                                      discretization::GlobalOrdinal, discretization::Node>;

// Records one row of the convergence table per Newton iteration; with `diagnosed` (a system with contact), a line under
// it on the contact points the iteration's full step carries across the law's inflection and the energy along that
// step (front_diagnosis.hpp).
class TableObserver : public NOX::Observer {
public:
  TableObserver(NewtonResult& result, const LinearSolverFactory& linear, std::ostream* table,
                const SpatulaModel* diagnosed)
      : result_(result), linear_(linear), table_(table), diagnosed_(diagnosed), start_(std::chrono::steady_clock::now())
  {
  }

  void runPreSolve(const NOX::Solver::Generic& solver) override
  {
    result_.initial_residual_norm = solver.getSolutionGroup().getNormF();
    if (table_)
      *table_ << "    newton    |f| [nN]     |dx|_inf      step   neg.piv   time [s]   slope ratio\n"
              << "    " << std::setw(6) << 0 << "  " << std::scientific << std::setprecision(3)
              << result_.initial_residual_norm << std::defaultfloat << "\n";
  }

  void runPostIterate(const NOX::Solver::Generic& solver) override
  {
    NewtonIteration row;
    row.iteration = solver.getNumIterations();
    const auto& current = solver.getSolutionGroup();
    row.residual_norm = current.getNormF();
    auto update = current.getX().clone(NOX::DeepCopy);
    update->update(-1.0, solver.getPreviousSolutionGroup().getX(), 1.0);
    row.update_norm = update->norm(NOX::Abstract::Vector::MaxNorm);
    const double slope_before = solver.getPreviousSolutionGroup().getF().innerProduct(*update);
    if (slope_before != 0.0) row.slope_ratio = current.getF().innerProduct(*update) / slope_before;
    if (const auto* line_search = dynamic_cast<const NOX::Solver::LineSearchBased*>(&solver))
      row.step = line_search->getStepSize();
    row.negative_pivots = linear_.mumps_statistics().negative_pivots;
    row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    result_.iterations.push_back(row);
    if (table_ && result_.elimination.applications > applications_) {
      applications_ = result_.elimination.applications;
      *table_ << "      front: " << result_.elimination.last_nodes << " nodes relaxed, |f| there x "
              << std::setprecision(3) << result_.elimination.last_reduction << " (" << result_.elimination.local_iterations
              << " local iterations so far)\n";
    }
    if (table_ && result_.elimination.limited_steps > limited_) {
      limited_ = result_.elimination.limited_steps;
      *table_ << "      front-limited step: " << result_.elimination.last_limited_points
              << " contact points held at the limit, their gap change x " << std::setprecision(3)
              << result_.elimination.last_kept << "\n";
    }
    if (table_)
      *table_ << "    " << std::setw(6) << row.iteration << "  " << std::scientific << std::setprecision(3)
              << row.residual_norm << "  " << row.update_norm << "  " << std::defaultfloat << std::setprecision(3)
              << std::setw(6) << row.step << "  " << std::setw(7) << row.negative_pivots << "  " << std::setw(8)
              << row.seconds << "  " << std::setw(10) << row.slope_ratio << "\n";
    if (table_ && diagnosed_ && row.step > 0.0) *table_ << front_line(full_step(solver, row.step));
  }

private:
  // The diagnosis of the iteration's full Newton step: from the previous state along (x - previous) / step.
  FrontDiagnosis full_step(const NOX::Solver::Generic& solver, double step) const
  {
    const auto tpetra = [](const NOX::Abstract::Vector& v) {
      return Extract::getConstTpetraVector(dynamic_cast<const NOX::Thyra::Vector&>(v).getThyraRCPVector());
    };
    const auto previous = tpetra(solver.getPreviousSolutionGroup().getX());
    const auto current = tpetra(solver.getSolutionGroup().getX());
    discretization::Vector full(previous->getMap());
    full.update(1.0 - 1.0 / step, *previous, 1.0 / step, *current, 0.0);
    return diagnose_front(*diagnosed_, *previous, full);
  }

  NewtonResult& result_;
  const LinearSolverFactory& linear_;
  std::ostream* table_;
  const SpatulaModel* diagnosed_;
  std::chrono::steady_clock::time_point start_;
  int applications_ = 0;
  int limited_ = 0;
};

}  // namespace

Teuchos::RCP<NOX::Observer> convergence_table(NewtonResult& result, const LinearSolverFactory& linear,
                                              std::ostream* table, const SpatulaModel* diagnosed)
{
  return Teuchos::rcp(new TableObserver(result, linear, table, diagnosed));
}

}  // namespace spatula::solvers
