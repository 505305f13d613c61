#include "solvers/newton.hpp"

#include "parameters/parameter_validation.hpp"
#include "solvers/attempt_tests.hpp"
#include "solvers/convergence_table.hpp"
#include "solvers/nox_energy_line_search.hpp"

#include <NOX_Solver_Factory.H>
#include <NOX_Solver_Generic.H>
#include <NOX_StatusTest_Combo.H>
#include <NOX_StatusTest_FiniteValue.H>
#include <NOX_StatusTest_MaxIters.H>
#include <NOX_StatusTest_NormF.H>
#include <NOX_StatusTest_NormUpdate.H>
#include <NOX_Thyra_Group.H>
#include <NOX_Thyra_Vector.H>
#include <Teuchos_TimeMonitor.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>

#include <cmath>
#include <ostream>
#include <string>

namespace spatula::solvers {

using discretization::GlobalOrdinal;
using discretization::LocalOrdinal;
using discretization::Node;
using Extract = Thyra::TpetraOperatorVectorExtraction<double, LocalOrdinal, GlobalOrdinal, Node>;

const std::vector<std::string>& line_search_names()
{
  static const std::vector<std::string> names = {"backtrack", "polynomial", "full step", "energy"};
  return names;
}

void NewtonParameters::declare(Teuchos::ParameterList& list)
{
  const NewtonParameters d;   // the defaults
  using parameters::Range;
  parameters::declare_double(list, "relative tolerance", d.relative_tolerance,
                             "|f| relative to its value at the step start",
                             {0.0, 1.0, false, true});
  // The default saves the last Newton iteration of most steps, which would take |f| far below what any reported
  // digit depends on (what a tighter value costs: docs/solvers.md).
  parameters::declare_double(list, "absolute tolerance", d.absolute_tolerance,
                             "|f|_2 [nN] (over sqrt(n) with norms = scaled)",
                             Range::non_negative());
  parameters::declare_double(list, "update tolerance", d.update_tolerance,
                             "|dx|_inf [nm, rad] (over n with norms = scaled)",
                             Range::positive());
  parameters::declare_int(list, "maximum iterations", d.maximum_iterations,
                          "Newton iterations per load step (fail fast, cut the step)",
                          Range::closed(1, 500));
  parameters::declare_int(list, "converging extension", d.converging_extension,
                          "iterations an attempt at 'maximum iterations' may go on while each of its last two "
                          "iterations cut |f| to 'contraction' or less (0: fail at the limit)",
                          Range::closed(0, 500));
  // energy by default: at the peel front Newton's steps fall short along their line (the energy's slope keeps a
  // quarter to a third of its value at the step's end), and backtracking on |f| would halve some of them.
  parameters::declare_string(list, "line search", parameters::name_of(d.line_search, line_search_names()),
                             "step length control: backtrack or polynomial (cut the step until |f| falls), full step, "
                             "or energy (the zero of the energy's slope along Newton's direction, steps up to 4: "
                             "backtrack where the direction does not lower the energy)", line_search_names());
  // 2 x 0.5, applied only after a failed step ('give up'): near a fold most retries are hopeless, while on a smooth
  // path a first attempt that shrinks |f| slowly for a few iterations still converges (docs/solvers.md).
  parameters::declare_int(list, "non-contracting iterations", d.non_contracting_iterations,
                          "give up on a load step after this many consecutive iterations that did not shrink |f| "
                          "below 'contraction' times its value before while |f| was above 1e-3 of its first value (0: "
                          "only 'maximum iterations' ends a step)",
                          Range::closed(0, 500));
  parameters::declare_string(list, "give up", d.give_up_only_after_failure ? "after a failed step" : "always",
                             "where the 'non-contracting iterations' rule applies: after a failed step (only in the "
                             "attempts that retry a load after a step failed, i.e. near a fold; a first attempt at "
                             "a large increment on a smooth path keeps every iteration) or always",
                             {"after a failed step", "always"});
  parameters::declare_double(list, "contraction", d.contraction,
                             "|f_k| / |f_k-1| at or above which an iteration counts as non-contracting",
                             {0.0, 10.0, true, false});
  parameters::declare_double(list, "give up above tolerance", d.give_up_above_tolerance,
                             "the give-up rules ('non-contracting iterations', 'short steps') count an iteration only "
                             "while |f| is above this multiple of 'absolute tolerance' (in the norm applied); 0: at "
                             "any |f|", Range::closed(0.0, 1e12));
  // 2 x 0.125 in every attempt: on the coarse pull-off at 45 deg it ends the hopeless first attempts at a fold
  // (12 iterations before) and no converging one, here or on xml/pull-off-medium.xml (benchmarks/step_control.py).
  parameters::declare_int(list, "short steps", d.short_steps,
                          "give up on a load step after this many consecutive iterations whose line search cut the "
                          "step to at most 'short step' while |f| was above 1e-3 of its first value (0: off)",
                          Range::closed(0, 500));
  parameters::declare_double(list, "short step", d.short_step,
                             "line-search step length at or below which an iteration counts for 'short steps'",
                             {0.0, 1.0, false, false});
  // Default Eisenstat-Walker: on the coarse pull-offs at 60 / 45 deg 36 / 33 % fewer MUMPS solves, 38 / 31 % fewer
  // factorizations, CPU 0.85 / 0.96 of constant, results within 0.004 % (benchmarks/step_control.py).
  parameters::declare_string(list, "forcing term", d.inexact ? "Eisenstat-Walker" : "constant",
                             "how accurately each linear system is solved: constant (to 'Linear Solver/tolerance' "
                             "always) or Eisenstat-Walker (NOX's type 2: relative tolerance 0.9 (|f_k| / |f_k-1|)^1.5 "
                             "between 'Linear Solver/tolerance' and 0.01; matters where GMRES runs on a lagged "
                             "factorization)", {"constant", "Eisenstat-Walker"});
  parameters::declare_string(list, "norms", d.scaled_norms ? "scaled" : "unscaled",
                             "how the absolute and update tolerances are applied: scaled (NOX's default, as every "
                             "recorded result ran) |f|_2 / sqrt(n) and |dx|_inf / n with n unknowns; unscaled: |f|_2 "
                             "and |dx|_inf themselves", {"scaled", "unscaled"});
  parameters::declare_bool(list, "front diagnosis", d.front_diagnosis,
                           "with Output/convergence tables: under each Newton iteration, the contact points its full "
                           "step carries across the law's inflection (count, where they sit, their share of the "
                           "adhesion energy's change) and the energy along that step at a quarter, half, three "
                           "quarters and all of it (five more evaluations per iteration)");
  FrontEliminationParameters::declare(parameters::declare_sublist(
      list, "Front Elimination", "nonlinear elimination of the unknowns where the residual concentrates"));
}

NewtonParameters NewtonParameters::from(const Teuchos::ParameterList& list)
{
  NewtonParameters p;
  p.relative_tolerance = list.get<double>("relative tolerance");
  p.absolute_tolerance = list.get<double>("absolute tolerance");
  p.update_tolerance = list.get<double>("update tolerance");
  p.maximum_iterations = list.get<int>("maximum iterations");
  p.converging_extension = list.get<int>("converging extension");
  p.line_search = parameters::choice<LineSearch>(list, "line search", line_search_names());
  p.scaled_norms = list.get<std::string>("norms") == "scaled";
  p.inexact = list.get<std::string>("forcing term") == "Eisenstat-Walker";
  p.non_contracting_iterations = list.get<int>("non-contracting iterations");
  p.contraction = list.get<double>("contraction");
  p.give_up_above_tolerance = list.get<double>("give up above tolerance");
  p.give_up_only_after_failure = list.get<std::string>("give up") == "after a failed step";
  p.short_steps = list.get<int>("short steps");
  p.short_step = list.get<double>("short step");
  p.front_diagnosis = list.get<bool>("front diagnosis");
  p.elimination = FrontEliminationParameters::from(list.sublist("Front Elimination"));
  return p;
}

namespace {

// The tests that end one attempt: converged (|f| below the absolute or relative tolerance and |dx| below its
// tolerance), the iteration limit, a non-finite value, and the give-up rules (after a failed step, or always).
struct Tests {
  Teuchos::RCP<NOX::StatusTest::Combo> all;
  Teuchos::RCP<NOX::StatusTest::Generic> short_steps;   // (null: the rule is off)
  bool give_up = false;
};

Tests attempt_tests(const NewtonParameters& parameters, NOX::Abstract::Group& start, bool after_failure)
{
  using namespace NOX::StatusTest;
  const auto scale = parameters.scaled_norms ? NormF::Scaled : NormF::Unscaled;
  auto absolute = Teuchos::rcp(new NormF(parameters.absolute_tolerance, scale));
  auto relative = Teuchos::rcp(new NormF(start, parameters.relative_tolerance, scale));
  auto residual = Teuchos::rcp(new Combo(Combo::OR, absolute, relative));
  auto update = Teuchos::rcp(new NormUpdate(parameters.update_tolerance, NOX::Abstract::Vector::MaxNorm,
                                            parameters.scaled_norms ? NormUpdate::Scaled : NormUpdate::Unscaled));
  Tests tests;
  tests.all = Teuchos::rcp(new Combo(Combo::OR));
  tests.all->addStatusTest(Teuchos::rcp(new Combo(Combo::AND, residual, update)));
  tests.all->addStatusTest(
      iteration_limit_test(parameters.maximum_iterations, parameters.converging_extension, parameters.contraction));
  tests.all->addStatusTest(Teuchos::rcp(new FiniteValue));
  constexpr double hopeless_above = 1e-3;   // of the attempt's first |f|: below it an attempt is converging
  // ... as it is below a few times the absolute tolerance, in |f|_2 (NOX's scaled test is |f|_2 / sqrt(n))
  const double floor = parameters.give_up_above_tolerance * parameters.absolute_tolerance *
                       (parameters.scaled_norms ? std::sqrt(double(start.getF().length())) : 1.0);
  tests.give_up = parameters.non_contracting_iterations > 0 && (after_failure || !parameters.give_up_only_after_failure);
  if (tests.give_up)   // far from a solution (past a fold): give up early
    tests.all->addStatusTest(give_up_test(
        "hopeless attempt (|f| not shrinking)", parameters.non_contracting_iterations, hopeless_above, floor,
        [contraction = parameters.contraction](double now, double before, double) {
          return now >= contraction * before;
        }));
  if (parameters.short_steps > 0) {
    tests.short_steps = give_up_test("short line-search steps", parameters.short_steps, hopeless_above, floor,
                                     [short_step = parameters.short_step](double, double, double step) {
                                       return step <= short_step;
                                     });
    tests.all->addStatusTest(tests.short_steps);
  }
  return tests;
}

// NOX's parameters: line-search Newton with the chosen line search (ours: the energy's), the front's elimination
// where asked, the linear tolerance (fixed or Eisenstat-Walker's), and the convergence table as its observer.
Teuchos::RCP<Teuchos::ParameterList> nox_parameters(const NewtonParameters& parameters, const LinearSolverFactory& linear,
                                                    SpatulaModel& model, NewtonResult& result, std::ostream* table)
{
  auto list = Teuchos::rcp(new Teuchos::ParameterList("NOX"));
  list->set("Nonlinear Solver", "Line Search Based");
  static const char* const nox_methods[] = {"Backtrack", "Polynomial", "Full Step", "User Defined"};   // LineSearch's
  const std::string method = nox_methods[static_cast<int>(parameters.line_search)];
  auto& line_search = list->sublist("Line Search");
  line_search.set("Method", method);
  if (parameters.line_search == LineSearch::energy)
    line_search.set<Teuchos::RCP<NOX::LineSearch::UserDefinedFactory>>(
        "User Defined Line Search Factory", energy_line_search_factory(model, parameters.elimination, result.elimination));
  // When no step reduces |f|, NOX takes its recovery step (a full step); adhesion problems often need it (|f| is
  // not monotone along good Newton steps). A non-finite or inverted result is caught by the model instead.
  for (const char* kind : {"Backtrack", "Polynomial"}) {
    auto& sub = line_search.sublist(kind);
    sub.set("Max Iters", 12);
    sub.set("Minimum Step", 1e-4);
  }
  list->sublist("Direction").set("Method", "Newton");
  if (parameters.elimination.use == EliminationUse::before_direction ||
      parameters.elimination.use == EliminationUse::soft_mode ||
      parameters.elimination.use == EliminationUse::front_limited_step) {
    list->sublist("Direction").set("Method", "User Defined");
    list->sublist("Direction").set<Teuchos::RCP<NOX::Direction::UserDefinedFactory>>(
        "User Defined Direction Factory",
        Teuchos::rcp(new FrontEliminationFactory(model, parameters.elimination, result.elimination)));
  }
  auto& newton = list->sublist("Direction").sublist("Newton");
  newton.sublist("Linear Solver").set("Tolerance", linear.parameters().tolerance);
  if (parameters.inexact) {   // NOX sets the linear tolerance of every iteration from the last contraction
    newton.set("Forcing Term Method", "Type 2");
    newton.set("Forcing Term Initial Tolerance", 1e-4);
    newton.set("Forcing Term Minimum Tolerance", linear.parameters().tolerance);
    newton.set("Forcing Term Maximum Tolerance", 0.01);
  }
  list->sublist("Printing").set("Output Information", 0);
  list->sublist("Solver Options").set<Teuchos::RCP<NOX::Observer>>(
      "Observer", convergence_table(result, linear, table,
                                    parameters.front_diagnosis && model.system().contact_area() > 0.0 ? &model : nullptr));
  return list;
}

}  // namespace

NewtonSolver::NewtonSolver(Teuchos::RCP<SpatulaModel> model, const NewtonParameters& parameters,
                           const LinearSolverFactory& linear_solver)
    : model_(std::move(model)), parameters_(parameters), linear_solver_(linear_solver)
{
}

NewtonResult NewtonSolver::solve(discretization::Vector& x, std::ostream* table, bool after_failure) const
{
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: newton"));
  NewtonResult result;
  const auto space = model_->get_x_space();
  auto start = Teuchos::rcp(new discretization::Vector(x, Teuchos::Copy));
  NOX::Thyra::Vector initial_guess(Thyra::createVector(start, space));
  auto group = Teuchos::rcp(new NOX::Thyra::Group(initial_guess, model_));

  group->computeF();
  const Tests tests = attempt_tests(parameters_, *group, after_failure);
  const auto list = nox_parameters(parameters_, linear_solver_, *model_, result, table);

  auto solver = NOX::Solver::buildSolver(group, tests.all, list);
  NOX::StatusTest::StatusType status = NOX::StatusTest::Unconverged;
  try {
    status = solver->solve();
  } catch (const std::bad_alloc&) {
    throw;   // an allocation failure is not a failed step: no shorter increment would need less memory
  } catch (const std::exception& error) {
    result.failure = std::string("exception in the Newton iteration: ") + error.what();
    return result;
  }
  if (status != NOX::StatusTest::Converged) {
    const auto& final_group = solver->getSolutionGroup();
    const bool cut_short = tests.short_steps && tests.short_steps->getStatus() == NOX::StatusTest::Failed;
    const bool stagnated = status == NOX::StatusTest::Failed && tests.give_up && !cut_short &&
                           solver->getNumIterations() < parameters_.maximum_iterations;   // (not the limit)
    result.failure = "no convergence after " + std::to_string(solver->getNumIterations()) + " iterations (" +
                     (stagnated ? "|f| stopped shrinking, " : "") +
                     (cut_short ? "the line search cut the steps short, " : "") +
                     "|f| = " + std::to_string(final_group.getNormF()) + " nN" +
                     (model_->last_evaluation().admissible ? "" : ", an element inverted") + ")";
    return result;
  }
  const auto& solution = dynamic_cast<const NOX::Thyra::Vector&>(solver->getSolutionGroup().getX());
  x.assign(*Extract::getConstTpetraVector(solution.getThyraRCPVector()));
  result.converged = true;
  return result;
}

}  // namespace spatula::solvers
