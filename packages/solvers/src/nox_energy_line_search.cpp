#include "solvers/nox_energy_line_search.hpp"

#include "solvers/energy_line_search.hpp"

#include <NOX_LineSearch_Backtrack.H>
#include <NOX_LineSearch_Generic.H>
#include <NOX_Abstract_Group.H>
#include <NOX_Solver_Generic.H>
#include <NOX_Thyra_Vector.H>
#include <Thyra_TpetraThyraWrappers.hpp>

namespace spatula::solvers {

namespace {

using Extract = Thyra::TpetraOperatorVectorExtraction<double, discretization::LocalOrdinal,
                                                      discretization::GlobalOrdinal, discretization::Node>;

// The energy line search as NOX calls it: the direction d from the previous group, phi'(alpha) = f(x + alpha d) . d,
// the energy Pi_int + Pi_c of the model's evaluation of that residual (the model's last evaluation on entry is the
// tangent's, at x). Where d does not lower the energy (phi'(0) >= 0: an indefinite tangent past a fold) or no
// admissible point was found, NOX's backtracking on |f| takes the step.
class EnergyLineSearch : public NOX::LineSearch::Generic {
public:
  EnergyLineSearch(const SpatulaModel& model, Teuchos::RCP<NOX::LineSearch::Generic> fallback,
                   const FrontEliminationParameters& elimination, EliminationCounts& counts)
      : model_(model), fallback_(std::move(fallback)), elimination_(elimination), counts_(counts)
  {
  }

  bool compute(NOX::Abstract::Group& group, double& step, const NOX::Abstract::Vector& direction,
               const NOX::Solver::Generic& solver) override
  {
    const auto& previous = solver.getPreviousSolutionGroup();
    const LinePoint origin{0.0, previous.getF().innerProduct(direction), model_.last_evaluation().energy(), true};
    if (!(origin.slope < 0.0)) return fallback_->compute(group, step, direction, solver);
    double evaluated = 0.0;
    const auto evaluate = [&](double alpha) {
      group.computeX(previous, direction, alpha);
      group.computeF();
      evaluated = alpha;
      const auto& evaluation = model_.last_evaluation();
      return LinePoint{alpha, evaluation.admissible ? group.getF().innerProduct(direction) : 0.0,
                       evaluation.energy(), evaluation.admissible};
    };
    if (elimination_.use == EliminationUse::after_full_step) {
      const LinePoint full = evaluate(1.0);
      const bool past = !full.admissible || full.slope > 0.0 || full.energy > origin.energy;
      if (past && full.admissible) {   // relax the nodes the full step carried too far, from the full step
        const auto& thyra_x = dynamic_cast<const NOX::Thyra::Vector&>(group.getX());
        const auto& thyra_f = dynamic_cast<const NOX::Thyra::Vector&>(group.getF());
        auto x = Teuchos::rcp(
            new discretization::Vector(*Extract::getConstTpetraVector(thyra_x.getThyraRCPVector()), Teuchos::Copy));
        discretization::Vector f(*Extract::getConstTpetraVector(thyra_f.getThyraRCPVector()), Teuchos::Copy);
        if (relax_front(model_, *x, f, elimination_, counts_) && model_.last_evaluation().admissible &&
            model_.last_evaluation().energy() < origin.energy) {
          group.setX(NOX::Thyra::Vector(Thyra::createVector(x, thyra_x.getThyraRCPVector()->space())));
          group.computeF();
          step = 1.0;
          return true;
        }
      }
    }
    const LinePoint chosen = search_energy_line(evaluate, origin, EnergyLineSearchParameters{});
    if (!chosen.admissible) return fallback_->compute(group, step, direction, solver);
    if (chosen.step != evaluated) evaluate(chosen.step);
    step = chosen.step;
    return true;
  }

private:
  const SpatulaModel& model_;
  Teuchos::RCP<NOX::LineSearch::Generic> fallback_;
  FrontEliminationParameters elimination_;
  EliminationCounts& counts_;
};

class EnergyLineSearchFactory : public NOX::LineSearch::UserDefinedFactory {
public:
  EnergyLineSearchFactory(const SpatulaModel& model, const FrontEliminationParameters& elimination,
                          EliminationCounts& counts)
      : model_(model), elimination_(elimination), counts_(counts)
  {
  }
  Teuchos::RCP<NOX::LineSearch::Generic> buildLineSearch(const Teuchos::RCP<NOX::GlobalData>& data,
                                                         Teuchos::ParameterList& list) const override
  {
    return Teuchos::rcp(new EnergyLineSearch(model_, Teuchos::rcp(new NOX::LineSearch::Backtrack(data, list)),
                                             elimination_, counts_));
  }

private:
  const SpatulaModel& model_;
  FrontEliminationParameters elimination_;
  EliminationCounts& counts_;
};

}  // namespace

Teuchos::RCP<NOX::LineSearch::UserDefinedFactory> energy_line_search_factory(
    const SpatulaModel& model, const FrontEliminationParameters& elimination, EliminationCounts& counts)
{
  return Teuchos::rcp(new EnergyLineSearchFactory(model, elimination, counts));
}

}  // namespace spatula::solvers
