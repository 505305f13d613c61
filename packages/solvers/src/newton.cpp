#include "solvers/newton.hpp"

#include "parameters/parameter_validation.hpp"
#include "solvers/energy_line_search.hpp"
#include "solvers/front_diagnosis.hpp"

#include <NOX_LineSearch_Backtrack.H>
#include <NOX_LineSearch_Generic.H>
#include <NOX_LineSearch_UserDefinedFactory.H>
#include <NOX_Observer.hpp>
#include <NOX_Solver_Factory.H>
#include <NOX_Solver_Generic.H>
#include <NOX_Solver_LineSearchBased.H>
#include <NOX_StatusTest_Combo.H>
#include <NOX_StatusTest_FiniteValue.H>
#include <NOX_StatusTest_MaxIters.H>
#include <NOX_StatusTest_NormF.H>
#include <NOX_StatusTest_NormUpdate.H>
#include <NOX_Thyra_Group.H>
#include <NOX_Thyra_Vector.H>
#include <Teuchos_TimeMonitor.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>

#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
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

// Records one row of the convergence table per Newton iteration; with `model` (a system with contact), a line under
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
};

// Gives up on a Newton attempt once `limit` iterations in a row met its rule while |f| was still above `far` times
// the residual the attempt started from. Two rules: hopeless (|f| left above `contraction` times its value before)
// and short steps (the line search cut the step to at most `short step`: Newton's direction does not lower |f|).
// The far condition spares the slow last iterations of a converging attempt (a nearly singular tangent at a peel
// front converges linearly, many orders below where it began); near a fold a hopeless attempt stays near its start.
class GiveUp : public NOX::StatusTest::Generic {
public:
  // Whether an iteration counts, from |f| now, |f| before and the line-search step (1 without a line search).
  using Rule = std::function<bool(double now, double before, double step)>;
  // An iteration counts while |f| >= far |f_0| and |f| >= floor.
  GiveUp(std::string description, int limit, double far, double floor, Rule rule)
      : description_(std::move(description)), limit_(limit), far_(far), floor_(floor), rule_(std::move(rule))
  {
  }

  NOX::StatusTest::StatusType checkStatus(const NOX::Solver::Generic& solver, NOX::StatusTest::CheckType) override
  {
    const int iteration = solver.getNumIterations();
    if (iteration == 0) {   // a new attempt
      start_ = solver.getSolutionGroup().getNormF();
      count_ = last_ = 0;
      status_ = NOX::StatusTest::Unconverged;
      return status_;
    }
    if (iteration == last_) return status_;   // asked twice in one iteration
    last_ = iteration;
    const double now = solver.getSolutionGroup().getNormF(), before = solver.getPreviousSolutionGroup().getNormF();
    const auto* line_search = dynamic_cast<const NOX::Solver::LineSearchBased*>(&solver);
    const double step = line_search ? line_search->getStepSize() : 1.0;
    count_ = now >= far_ * start_ && now >= floor_ && rule_(now, before, step) ? count_ + 1 : 0;
    status_ = count_ >= limit_ ? NOX::StatusTest::Failed : NOX::StatusTest::Unconverged;
    return status_;
  }
  NOX::StatusTest::StatusType getStatus() const override { return status_; }
  std::ostream& print(std::ostream& stream, int indent) const override
  {
    return stream << std::string(indent, ' ') << status_ << " " << description_ << ": " << count_ << " of " << limit_
                  << " iterations in a row\n";
  }

private:
  std::string description_;
  int limit_;
  double far_, floor_;
  Rule rule_;
  double start_ = 0.0;
  int count_ = 0, last_ = 0;
  NOX::StatusTest::StatusType status_ = NOX::StatusTest::Unconverged;
};

// The iteration limit of an attempt, spared while it converges: at `limit` iterations an attempt fails unless each of
// its last two iterations cut |f| to `contraction` of its value before or less; such an attempt goes on, at most
// `extension` iterations more. At the medium peel front an attempt often needs 13-14 iterations, the last few
// converging fast: failing it at 12 threw its iterations away and the cut increments that followed bisected towards a
// load that was no limit point (docs/performance.md, "The peel front").
class IterationLimit : public NOX::StatusTest::Generic {
public:
  IterationLimit(int limit, int extension, double contraction)
      : limit_(limit), extension_(extension), contraction_(contraction)
  {
  }
  NOX::StatusTest::StatusType checkStatus(const NOX::Solver::Generic& solver, NOX::StatusTest::CheckType) override
  {
    const int iteration = solver.getNumIterations();
    if (iteration == 0) {
      older_ratio_ = 1.0;
      last_ = 0;
      status_ = NOX::StatusTest::Unconverged;
      return status_;
    }
    if (iteration == last_) return status_;   // asked twice in one iteration
    last_ = iteration;
    const double before = solver.getPreviousSolutionGroup().getNormF();
    const double ratio = before > 0.0 ? solver.getSolutionGroup().getNormF() / before : 1.0;
    const bool converging = ratio <= contraction_ && older_ratio_ <= contraction_;
    older_ratio_ = ratio;
    const bool spent = iteration >= limit_ + extension_ || (iteration >= limit_ && !converging);
    status_ = spent ? NOX::StatusTest::Failed : NOX::StatusTest::Unconverged;
    return status_;
  }
  NOX::StatusTest::StatusType getStatus() const override { return status_; }
  std::ostream& print(std::ostream& stream, int indent) const override
  {
    return stream << std::string(indent, ' ') << status_ << " iteration limit " << limit_ << " (+" << extension_
                  << " while converging)\n";
  }

private:
  int limit_, extension_;
  double contraction_;
  double older_ratio_ = 1.0;
  int last_ = 0;
  NOX::StatusTest::StatusType status_ = NOX::StatusTest::Unconverged;
};

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

  using namespace NOX::StatusTest;
  const auto scale = parameters_.scaled_norms ? NormF::Scaled : NormF::Unscaled;
  auto absolute = Teuchos::rcp(new NormF(parameters_.absolute_tolerance, scale));
  group->computeF();
  auto relative = Teuchos::rcp(new NormF(*group, parameters_.relative_tolerance, scale));
  auto residual = Teuchos::rcp(new Combo(Combo::OR, absolute, relative));
  auto update = Teuchos::rcp(new NormUpdate(parameters_.update_tolerance, NOX::Abstract::Vector::MaxNorm,
                                            parameters_.scaled_norms ? NormUpdate::Scaled : NormUpdate::Unscaled));
  auto converged = Teuchos::rcp(new Combo(Combo::AND, residual, update));
  auto tests = Teuchos::rcp(new Combo(Combo::OR));
  tests->addStatusTest(converged);
  tests->addStatusTest(Teuchos::rcp(
      new IterationLimit(parameters_.maximum_iterations, parameters_.converging_extension, parameters_.contraction)));
  tests->addStatusTest(Teuchos::rcp(new FiniteValue));
  constexpr double hopeless_above = 1e-3;   // of the attempt's first |f|: below it an attempt is converging
  // ... as it is below a few times the absolute tolerance, in |f|_2 (NOX's scaled test is |f|_2 / sqrt(n))
  const double floor = parameters_.give_up_above_tolerance * parameters_.absolute_tolerance *
                       (parameters_.scaled_norms ? std::sqrt(double(group->getF().length())) : 1.0);
  const bool give_up = parameters_.non_contracting_iterations > 0 &&
                       (after_failure || !parameters_.give_up_only_after_failure);
  if (give_up)   // far from a solution (past a fold): give up early
    tests->addStatusTest(Teuchos::rcp(new GiveUp(
        "hopeless attempt (|f| not shrinking)", parameters_.non_contracting_iterations, hopeless_above, floor,
        [contraction = parameters_.contraction](double now, double before, double) {
          return now >= contraction * before;
        })));
  Teuchos::RCP<GiveUp> short_steps;
  if (parameters_.short_steps > 0) {
    short_steps = Teuchos::rcp(new GiveUp("short line-search steps", parameters_.short_steps, hopeless_above, floor,
                                          [short_step = parameters_.short_step](double, double, double step) {
                                            return step <= short_step;
                                          }));
    tests->addStatusTest(short_steps);
  }

  auto list = Teuchos::rcp(new Teuchos::ParameterList("NOX"));
  list->set("Nonlinear Solver", "Line Search Based");
  static const char* const nox_methods[] = {"Backtrack", "Polynomial", "Full Step", "User Defined"};   // LineSearch's
  const std::string method = nox_methods[static_cast<int>(parameters_.line_search)];
  auto& line_search = list->sublist("Line Search");
  line_search.set("Method", method);
  if (parameters_.line_search == LineSearch::energy)
    line_search.set<Teuchos::RCP<NOX::LineSearch::UserDefinedFactory>>(
        "User Defined Line Search Factory", Teuchos::rcp(new EnergyLineSearchFactory(*model_, parameters_.elimination, result.elimination)));
  // When no step reduces |f|, NOX takes its recovery step (a full step); adhesion problems often need it (|f| is
  // not monotone along good Newton steps). A non-finite or inverted result is caught by the model instead.
  for (const char* kind : {"Backtrack", "Polynomial"}) {
    auto& sub = line_search.sublist(kind);
    sub.set("Max Iters", 12);
    sub.set("Minimum Step", 1e-4);
  }
  list->sublist("Direction").set("Method", "Newton");
  if (parameters_.elimination.use == EliminationUse::before_direction ||
      parameters_.elimination.use == EliminationUse::soft_mode) {
    list->sublist("Direction").set("Method", "User Defined");
    list->sublist("Direction").set<Teuchos::RCP<NOX::Direction::UserDefinedFactory>>(
        "User Defined Direction Factory",
        Teuchos::rcp(new FrontEliminationFactory(*model_, parameters_.elimination, result.elimination)));
  }
  auto& newton = list->sublist("Direction").sublist("Newton");
  newton.sublist("Linear Solver").set("Tolerance", linear_solver_.parameters().tolerance);
  if (parameters_.inexact) {   // NOX sets the linear tolerance of every iteration from the last contraction
    newton.set("Forcing Term Method", "Type 2");
    newton.set("Forcing Term Initial Tolerance", 1e-4);
    newton.set("Forcing Term Minimum Tolerance", linear_solver_.parameters().tolerance);
    newton.set("Forcing Term Maximum Tolerance", 0.01);
  }
  list->sublist("Printing").set("Output Information", 0);
  list->sublist("Solver Options").set<Teuchos::RCP<NOX::Observer>>(
      "Observer", Teuchos::rcp(new TableObserver(result, linear_solver_, table,
                                    parameters_.front_diagnosis && model_->system().contact_area() > 0.0 ? model_.get()
                                                                                                          : nullptr)));

  auto solver = NOX::Solver::buildSolver(group, tests, list);
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
    const bool cut_short = short_steps && short_steps->getStatus() == NOX::StatusTest::Failed;
    const bool stagnated = status == NOX::StatusTest::Failed && give_up && !cut_short &&
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
