#include "solvers/linear_solver.hpp"

#include "parameters/parameter_validation.hpp"
#include "solvers/inverse_preconditioner_factory.hpp"
#include "solvers/renewal_rule.hpp"

#include <Stratimikos_DefaultLinearSolverBuilder.hpp>
#include <Teuchos_AbstractFactoryStd.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Thyra_Ifpack2PreconditionerFactory.hpp>

#include <algorithm>

namespace spatula::solvers {

using discretization::GlobalOrdinal;
using discretization::LocalOrdinal;
using discretization::Node;

const std::vector<std::string>& linear_solver_names()
{
  static const std::vector<std::string> names = {"mumps", "gmres-ilu", "gmres-amg", "auto"};
  return names;
}

const std::vector<std::string>& refactor_rule_names()
{
  static const std::vector<std::string> names = {"lag", "cost", "clock"};
  return names;
}

double FactorWork::solve(const MumpsStatistics& statistics, bool symmetric)
{
  // Each stored entry is used once forward and once backward (L and L^T of LDL^T), or once (L and U of LU): two
  // operations each. A substitution streams the factors from memory, a factorization works in cache (BLAS-3): on
  // the medium mesh a factorization did 1.39e10 operations in 0.69 s and a solve 7.8e7 in 0.0305 s, an operation
  // of the solve 7.8 times as dear (docs/solvers.md, "Refactoring": how to measure it on another machine).
  constexpr double solve_weight = 8.0;
  return solve_weight * (symmetric ? 4.0 : 2.0) * statistics.factor_entries;
}

void LinearSolverParameters::declare(Teuchos::ParameterList& list)
{
  const LinearSolverParameters d;   // the defaults
  using parameters::Range;
  parameters::declare_string(list, "type", parameters::name_of(d.type, linear_solver_names()),
                             "linear solver of the Newton steps (auto: mumps while its factors fit in the memory "
                             "available, else gmres-amg)", linear_solver_names());
  parameters::declare_double(list, "tolerance", d.tolerance, "relative residual of each linear solve",
                             {0.0, 0.1, true, false});
  parameters::declare_int(list, "maximum iterations", d.maximum_iterations,
                          "Krylov iterations per solve (gmres-ilu, gmres-amg: a gmres-amg tangent whose solves take "
                          "that many V-cycles hands the later ones to MUMPS)",
                          Range::closed(1, 100000));
  parameters::declare_int(list, "ILU fill level", d.fill_level,
                          "level of fill of ILU(k) (gmres-ilu)", Range::closed(0, 8));
  MumpsParameters::declare(parameters::declare_sublist(list, "MUMPS", "direct solver options"),
                           LinearSolverParameters{}.mumps);
  parameters::declare_int(list, "lag", d.lag,
                          "mumps: Newton tangents one factorization may serve as preconditioner (0: refactor always)",
                          Range::closed(0, 1000));
  parameters::declare_int(list, "lag applications", d.lag_applications,
                          "mumps: refactor once the solves of one tangent needed more preconditioner applications",
                          Range::closed(1, 1000));
  parameters::declare_string(list, "refactor", parameters::name_of(d.refactor, refactor_rule_names()),
                             "mumps: when a kept factorization is replaced: lag (after 'lag' tangents or once a "
                             "tangent needed more than 'lag applications' solves), cost (once the last tangent's "
                             "solves cost more than the average per tangent of the factorization's cycle, "
                             "factorization included, counted from MUMPS' operation counts: the same path on a quiet "
                             "and a busy machine), or clock (the same from measured seconds: a busy machine changes "
                             "the path); with cost and clock also once a GMRES solve reached its iteration limit, and "
                             "'lag' and 'lag applications' are not used)",
                             refactor_rule_names());
}

LinearSolverParameters LinearSolverParameters::from(const Teuchos::ParameterList& list)
{
  LinearSolverParameters p;
  p.type = parameters::choice<LinearSolverType>(list, "type", linear_solver_names());
  p.tolerance = list.get<double>("tolerance");
  p.maximum_iterations = list.get<int>("maximum iterations");
  p.fill_level = list.get<int>("ILU fill level");
  p.mumps = MumpsParameters::from(list.sublist("MUMPS"));
  p.lag = list.get<int>("lag");
  p.lag_applications = list.get<int>("lag applications");
  p.refactor = parameters::choice<RefactorRule>(list, "refactor", refactor_rule_names());
  return p;
}

namespace {

// GMRES iterations per solve around MUMPS: an exact inverse needs one (a few more refine); old or low-rank factors more.
int gmres_limit(const LinearSolverParameters& p)
{
  const bool approximate =
      p.lag > 0 || p.refactor != RefactorRule::lag || p.mumps.low_rank_tolerance > 0.0 || p.mumps.single_precision;
  return approximate ? 60 : 10;
}

// MUMPS as a Thyra preconditioner: A^-1 itself. Keeps one MumpsSolver (and its symbolic analysis) per map.
class MumpsPreconditionerFactory : public InversePreconditionerFactory {
public:
  MumpsPreconditionerFactory(LinearSolverParameters parameters, std::shared_ptr<Teuchos::RCP<MumpsSolver>> solver,
                             std::shared_ptr<bool> renew)
      : InversePreconditionerFactory("MUMPS"), parameters_(std::move(parameters)), solver_(std::move(solver)),
        renew_(std::move(renew))
  {
  }

  void initializePrec(const Teuchos::RCP<const Thyra::LinearOpSourceBase<double>>& source,
                      Thyra::PreconditionerBase<double>* preconditioner,
                      const Thyra::ESupportSolveUse) const override
  {
    const auto matrix = matrix_of(*source);
    if (matrix.is_null()) throw std::logic_error("MUMPS preconditioner: operator is not a Tpetra CrsMatrix");
    auto& solver = *solver_;
    if (solver.is_null() || !solver->getDomainMap()->isSameAs(*matrix->getRowMap()))
      solver = Teuchos::rcp(new MumpsSolver(matrix->getRowMap(), parameters_.mumps));
    if (keep_factors(*solver, *matrix->getRowMap()->getComm())) {
      ++served_;
      solver->count_reuse();
    } else {
      solver->factor(*matrix);
      *renew_ = false;
      served_ = 0;
      const auto& statistics = solver->statistics();
      cost_.factored(parameters_.refactor == RefactorRule::clock ? statistics.last_factorization_seconds
                                                                 : FactorWork::factorization(statistics),
                     0.0);   // its tangent yields with its solves, at the next keep
    }
    applications_at_init_ = solver->statistics().applications_since_factor;
    solve_seconds_at_init_ = solver->statistics().solve_seconds;
    hold(*preconditioner, matrix->getRowMap(), solver);
  }

private:
  // Whether the current factors serve the next tangent too, decided from the solves of the previous tangent (they
  // ran with the current factors). Collective: refactoring is a collective call.
  bool keep_factors(const MumpsSolver& solver, const Teuchos::Comm<int>& comm) const
  {
    const auto& statistics = solver.statistics();
    if (statistics.factorizations == 0 || *renew_) return false;
    if (parameters_.refactor == RefactorRule::lag) {   // the same counts on every rank
      return parameters_.lag > 0 && served_ < parameters_.lag &&
             statistics.applications_since_factor - applications_at_init_ <= parameters_.lag_applications;
    }
    // Factors that no longer bring GMRES to its tolerance within its iteration limit are replaced whatever the
    // clock says (a capped solve costs the same every time, so the average would never rise above it).
    const int applications = statistics.applications_since_factor - applications_at_init_;
    const bool capped = applications >= gmres_limit(parameters_);
    const double last_cost = parameters_.refactor == RefactorRule::clock
                                 ? statistics.solve_seconds - solve_seconds_at_init_
                                 : applications * FactorWork::solve(statistics, parameters_.mumps.symmetric);
    int refactor = capped || !cost_.keep(last_cost, 1.0) ? 1 : 0;
    // The clocks differ by rank (the operation counts do not): any rank that would refactor decides for all.
    Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, refactor, Teuchos::outArg(refactor));
    return refactor == 0;
  }

  LinearSolverParameters parameters_;
  std::shared_ptr<Teuchos::RCP<MumpsSolver>> solver_;
  std::shared_ptr<bool> renew_;   // LinearSolverFactory::renew_factors
  mutable int served_ = 0, applications_at_init_ = 0;   // tangents the factors served after their own
  mutable double solve_seconds_at_init_ = 0.0;          // MUMPS solve time when the last tangent came
  mutable RenewalRule cost_;   // a tangent yields 1
};

// gmres-amg's preconditioner factories: each over the one hierarchy, with MUMPS as the fallback.
class MultigridFactoryCreator : public Teuchos::AbstractFactory<Thyra::PreconditionerFactoryBase<double>> {
public:
  MultigridFactoryCreator(LinearSolverParameters parameters, std::shared_ptr<const AlgebraicMultigrid> multigrid,
                          std::shared_ptr<Teuchos::RCP<MumpsSolver>> solver, std::shared_ptr<bool> renew)
      : parameters_(std::move(parameters)), multigrid_(std::move(multigrid)), solver_(std::move(solver)),
        renew_(std::move(renew))
  {
  }
  Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>> create() const override
  {
    return multigrid_->preconditioner_factory(
        Teuchos::rcp(new MumpsPreconditionerFactory(parameters_, solver_, renew_)));
  }

private:
  LinearSolverParameters parameters_;
  std::shared_ptr<const AlgebraicMultigrid> multigrid_;
  std::shared_ptr<Teuchos::RCP<MumpsSolver>> solver_;
  std::shared_ptr<bool> renew_;
};

class MumpsFactoryCreator : public Teuchos::AbstractFactory<Thyra::PreconditionerFactoryBase<double>> {
public:
  MumpsFactoryCreator(LinearSolverParameters parameters, std::shared_ptr<Teuchos::RCP<MumpsSolver>> solver,
                      std::shared_ptr<bool> renew)
      : parameters_(std::move(parameters)), solver_(std::move(solver)), renew_(std::move(renew))
  {
  }
  Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>> create() const override
  {
    return Teuchos::rcp(new MumpsPreconditionerFactory(parameters_, solver_, renew_));
  }

private:
  LinearSolverParameters parameters_;
  std::shared_ptr<Teuchos::RCP<MumpsSolver>> solver_;
  std::shared_ptr<bool> renew_;
};

Teuchos::RCP<Teuchos::ParameterList> stratimikos_list(const LinearSolverParameters& p)
{
  auto list = Teuchos::rcp(new Teuchos::ParameterList("Stratimikos"));
  list->set("Linear Solver Type", "Belos");
  auto& belos = list->sublist("Linear Solver Types").sublist("Belos");
  // Single-precision factors round each application anew (not one fixed linear operator): flexible GMRES keeps the
  // preconditioned vectors it combines, so its solution reaches the tolerance as with double-precision factors
  // (also gmres-amg's, whose MUMPS fallback has them).
  const bool flexible = p.type != LinearSolverType::gmres_ilu && p.mumps.single_precision;
  const char* solver = flexible ? "Block GMRES" : "Pseudo Block GMRES";
  belos.set("Solver Type", solver);
  auto& gmres = belos.sublist("Solver Types").sublist(solver);
  gmres.set("Convergence Tolerance", p.tolerance);
  if (flexible) gmres.set("Flexible Gmres", true);
  if (p.type == LinearSolverType::mumps) {
    gmres.set("Maximum Iterations", gmres_limit(p));
    gmres.set("Num Blocks", gmres_limit(p));
    list->set("Preconditioner Type", "MUMPS");
    return list;
  }
  gmres.set("Maximum Iterations", p.maximum_iterations);   // the iterative preconditioners
  gmres.set("Num Blocks", std::min(p.maximum_iterations, 200));
  if (p.type == LinearSolverType::gmres_amg) {
    list->set("Preconditioner Type", "AMG");
  } else {
    list->set("Preconditioner Type", "Ifpack2");
    auto& ifpack2 = list->sublist("Preconditioner Types").sublist("Ifpack2");
    ifpack2.set("Prec Type", "RILUK");   // on each rank's rows (block Jacobi between ranks)
    ifpack2.sublist("Ifpack2 Settings").set("fact: iluk level-of-fill", p.fill_level);
  }
  return list;
}

}  // namespace

struct LinearSolverFactory::Implementation {
  LinearSolverParameters parameters;
  std::shared_ptr<Teuchos::RCP<MumpsSolver>> mumps = std::make_shared<Teuchos::RCP<MumpsSolver>>();
  std::shared_ptr<bool> renew = std::make_shared<bool>(false);   // renew_factors()
  std::shared_ptr<const AlgebraicMultigrid> multigrid;   // gmres-amg only
  Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> factory;
  MumpsStatistics empty;
};

LinearSolverFactory::LinearSolverFactory(const LinearSolverParameters& parameters,
                                         std::shared_ptr<const NodeBlocks> node_blocks)
    : implementation_(std::make_unique<Implementation>())
{
  auto& impl = *implementation_;
  impl.parameters = parameters;
  if (parameters.type == LinearSolverType::automatic)
    throw std::logic_error("LinearSolverFactory: 'auto' must be resolved to a solver first");
  if (parameters.type == LinearSolverType::gmres_amg)
    impl.multigrid = std::make_shared<const AlgebraicMultigrid>(std::move(node_blocks), parameters.maximum_iterations);
  Stratimikos::DefaultLinearSolverBuilder builder;
  builder.setPreconditioningStrategyFactory(
      Teuchos::rcp(new MumpsFactoryCreator(parameters, impl.mumps, impl.renew)),
      "MUMPS");
  if (impl.multigrid)
    builder.setPreconditioningStrategyFactory(
        Teuchos::rcp(new MultigridFactoryCreator(parameters, impl.multigrid, impl.mumps, impl.renew)), "AMG");
  using Ifpack2Factory = Thyra::Ifpack2PreconditionerFactory<discretization::CrsMatrix>;
  builder.setPreconditioningStrategyFactory(
      Teuchos::abstractFactoryStd<Thyra::PreconditionerFactoryBase<double>, Ifpack2Factory>(), "Ifpack2");
  builder.setParameterList(stratimikos_list(parameters));
  impl.factory = builder.createLinearSolveStrategy("");
}

LinearSolverFactory::~LinearSolverFactory() = default;

void LinearSolverFactory::renew_factors() const { *implementation_->renew = true; }

Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> LinearSolverFactory::lows_factory() const
{
  return implementation_->factory;
}

const MumpsStatistics& LinearSolverFactory::mumps_statistics() const
{
  const auto& solver = *implementation_->mumps;
  return solver.is_null() ? implementation_->empty : solver->statistics();
}

const MultigridStatistics& LinearSolverFactory::multigrid_statistics() const
{
  static const MultigridStatistics none;
  return implementation_->multigrid ? implementation_->multigrid->statistics() : none;
}

const LinearSolverParameters& LinearSolverFactory::parameters() const { return implementation_->parameters; }

}  // namespace spatula::solvers
