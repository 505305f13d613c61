// The MUMPS wrapper on systems with known answers: a solve against a known solution, the inertia of a shifted
// Laplacian against its exact eigenvalues, reuse of the analysis, orderings, low-rank factors, and the linear solvers as NOX reaches them through Thyra.
#include "solvers/linear_solver.hpp"
#include "solvers/mumps_solver.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Thyra_LinearOpWithSolveFactoryHelpers.hpp>
#include <Thyra_TpetraLinearOp.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace spatula;
using discretization::CrsMatrix;
using discretization::GlobalOrdinal;
using discretization::Map;
using discretization::Vector;

constexpr double pi = 3.14159265358979323846;

// tridiag(-1, 2, -1) - shift I on n unknowns spread over the ranks; eigenvalues 2 - 2 cos(k pi / (n + 1)) - shift.
Teuchos::RCP<CrsMatrix> shifted_laplacian(GlobalOrdinal n, double shift)
{
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  auto map = Teuchos::rcp(new Map(n, 0, comm));
  auto matrix = Teuchos::rcp(new CrsMatrix(map, 3));
  for (std::size_t local = 0; local < map->getNodeNumElements(); ++local) {
    const GlobalOrdinal row = map->getGlobalElement(local);
    std::vector<GlobalOrdinal> columns{row};
    std::vector<double> values{2.0 - shift};
    if (row > 0) columns.push_back(row - 1), values.push_back(-1.0);
    if (row < n - 1) columns.push_back(row + 1), values.push_back(-1.0);
    matrix->insertGlobalValues(row, Teuchos::ArrayView<const GlobalOrdinal>(columns),
                               Teuchos::ArrayView<const double>(values));
  }
  matrix->fillComplete();
  return matrix;
}

int eigenvalues_below(GlobalOrdinal n, double shift)
{
  int count = 0;
  for (GlobalOrdinal k = 1; k <= n; ++k) count += 2.0 - 2.0 * std::cos(k * pi / (n + 1)) < shift;
  return count;
}

// |A x - b| / |b| for the solution x of A x = b by the factors, with b = A (1, 2, 3, ...).
double relative_residual(const CrsMatrix& matrix, solvers::MumpsSolver& mumps, double* error = nullptr)
{
  const auto map = matrix.getRowMap();
  Vector exact(map), b(map), x(map), check(map);
  for (std::size_t local = 0; local < map->getNodeNumElements(); ++local)
    exact.replaceLocalValue(local, 1.0 + map->getGlobalElement(local));
  matrix.apply(exact, b);
  mumps.apply(b, x);
  matrix.apply(x, check);
  check.update(-1.0, b, 1.0);
  if (error) {
    Vector difference(exact, Teuchos::Copy);
    difference.update(-1.0, x, 1.0);
    *error = difference.normInf() / exact.normInf();
  }
  return check.norm2() / b.norm2();
}

TEST(Mumps, SolvesASymmetricPositiveDefiniteSystem)
{
  const auto matrix = shifted_laplacian(200, 0.0);
  solvers::MumpsSolver mumps(matrix->getRowMap(), solvers::MumpsParameters{});
  mumps.factor(*matrix);
  double error = 0.0;
  EXPECT_LT(relative_residual(*matrix, mumps, &error), 1e-13);
  EXPECT_LT(error, 1e-9);   // condition number ~ 1.6e4
  EXPECT_EQ(mumps.statistics().negative_pivots, 0);
}

TEST(Mumps, InertiaOfAnIndefiniteSystemIsItsCountOfNegativeEigenvalues)
{
  const GlobalOrdinal n = 200;
  for (double shift : {0.05, 0.5, 1.3, 3.9}) {   // none within 1e-4 of an eigenvalue
    const auto matrix = shifted_laplacian(n, shift);
    solvers::MumpsSolver mumps(matrix->getRowMap(), solvers::MumpsParameters{});
    mumps.factor(*matrix);
    EXPECT_EQ(mumps.statistics().negative_pivots, eigenvalues_below(n, shift)) << "shift " << shift;
    EXPECT_LT(relative_residual(*matrix, mumps), 1e-10) << "shift " << shift;
  }
  EXPECT_EQ(eigenvalues_below(n, 0.5), 46);   // the counting itself: 2 - 2 cos(k pi / 201) < 0.5 for k <= 46
}

TEST(Mumps, LuModeSolvesTheIndefiniteSystemToo)
{
  const auto matrix = shifted_laplacian(120, 1.3);
  solvers::MumpsParameters parameters;
  parameters.symmetric = false;
  solvers::MumpsSolver mumps(matrix->getRowMap(), parameters);
  mumps.factor(*matrix);
  EXPECT_LT(relative_residual(*matrix, mumps), 1e-10);
  EXPECT_EQ(mumps.statistics().negative_pivots, -1);   // unknown in LU mode
}

TEST(Mumps, OneAnalysisServesEveryFactorizationOfThePattern)
{
  solvers::MumpsSolver mumps(shifted_laplacian(150, 0.0)->getRowMap(), solvers::MumpsParameters{});
  for (double shift : {0.0, 0.2, 0.7}) {
    const auto matrix = shifted_laplacian(150, shift);
    mumps.factor(*matrix);
    EXPECT_LT(relative_residual(*matrix, mumps), 1e-10);
  }
  EXPECT_EQ(mumps.statistics().analyses, 1);
  EXPECT_EQ(mumps.statistics().factorizations, 3);
  EXPECT_EQ(mumps.statistics().solves, 3);
  EXPECT_GT(mumps.statistics().factorization_flops, 0.0);
  EXPECT_GE(mumps.statistics().factor_entries, 150.0);   // at least the diagonal
}

TEST(Mumps, AnOrderingIsUsedAsAskedOrRefusedByName)
{
  const auto matrix = shifted_laplacian(100, 0.0);
  for (auto ordering : {solvers::MumpsOrdering::amd, solvers::MumpsOrdering::pord}) {
    solvers::MumpsParameters parameters;
    parameters.ordering = ordering;
    solvers::MumpsSolver mumps(matrix->getRowMap(), parameters);
    mumps.factor(*matrix);
    EXPECT_EQ(mumps.statistics().ordering_used, solvers::mumps_ordering_names()[static_cast<int>(ordering)]);
    EXPECT_LT(relative_residual(*matrix, mumps), 1e-12);
  }
  // METIS is not in Debian's MUMPS: the analysis names the key instead of silently ordering with another.
  solvers::MumpsParameters parameters;
  parameters.ordering = solvers::MumpsOrdering::metis;
  solvers::MumpsSolver mumps(matrix->getRowMap(), parameters);
  try {
    mumps.factor(*matrix);
    EXPECT_EQ(mumps.statistics().ordering_used, "METIS");   // a MUMPS built with METIS
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("'Linear Solver/MUMPS/ordering' = METIS"), std::string::npos)
        << error.what();
  }
}

TEST(Mumps, LowRankFactorsAreAnApproximateInverse)
{
  const auto matrix = shifted_laplacian(400, 0.0);
  solvers::MumpsParameters parameters;
  parameters.low_rank_tolerance = 1e-3;
  parameters.low_rank_from = 0;
  solvers::MumpsSolver mumps(matrix->getRowMap(), parameters);
  mumps.factor(*matrix);
  EXPECT_LT(relative_residual(*matrix, mumps), 1e-2);
  EXPECT_EQ(mumps.statistics().negative_pivots, 0);
  // Below 'low rank from' unknowns the factors are exact whatever the tolerance.
  parameters.low_rank_from = 401;
  solvers::MumpsSolver exact(matrix->getRowMap(), parameters);
  exact.factor(*matrix);
  EXPECT_LT(relative_residual(*matrix, exact), 1e-13);
}

TEST(Mumps, SinglePrecisionFactorsAreAnApproximateInverseWithTheSameInertia)
{
  // Ill-conditioned like the spatula's tangent (the smallest eigenvalue about 5e-6 of the largest): single-precision
  // factors solve it to about their rounding times the condition number, far from double's, and count the same
  // negative eigenvalues where none is near zero.
  const auto matrix = shifted_laplacian(700, 0.0);
  solvers::MumpsParameters parameters;
  parameters.single_precision = true;
  solvers::MumpsSolver single(matrix->getRowMap(), parameters);
  single.factor(*matrix);
  const double residual = relative_residual(*matrix, single);
  EXPECT_LT(residual, 1e-4);
  EXPECT_GT(residual, 1e-12);   // not double precision's
  EXPECT_EQ(single.statistics().negative_pivots, 0);
  const auto indefinite = shifted_laplacian(200, 0.5);
  solvers::MumpsSolver shifted(indefinite->getRowMap(), parameters);
  shifted.factor(*indefinite);
  EXPECT_EQ(shifted.statistics().negative_pivots, eigenvalues_below(200, 0.5));
  EXPECT_LT(relative_residual(*indefinite, shifted), 1e-4);
  // Users of the inertia take exact factors of the same options: LDL^T, full rank, double precision.
  parameters.symmetric = false;
  parameters.low_rank_tolerance = 1e-3;
  parameters.ordering = solvers::MumpsOrdering::pord;
  const auto exact = parameters.exact_ldlt();
  EXPECT_TRUE(exact.symmetric && !exact.single_precision && exact.low_rank_tolerance == 0.0);
  EXPECT_EQ(exact.ordering, solvers::MumpsOrdering::pord);
}

}  // namespace

// The solver the Newton iterations use, through Thyra as NOX calls it: each linear solver reaches the solution of a
// sequence of slowly changing systems (as Newton's tangents within a step),
// and the refactor rules decide as documented. The systems are tridiag(-1, 3 - 0.02 k, -1): well conditioned, so that
// old factors precondition each later one to a few GMRES iterations.
namespace {

struct SolveCounts {
  double worst_error = 0.0;   // |x - x_exact|_inf / |x_exact|_inf over the sequence
  int factorizations = 0, reused = 0;
};

SolveCounts solve_sequence(const solvers::LinearSolverParameters& parameters, GlobalOrdinal n = 300)
{
  using discretization::LocalOrdinal;
  using discretization::Node;
  solvers::LinearSolverFactory factory(parameters);
  const auto map = shifted_laplacian(n, 0.0)->getRowMap();
  const auto tpetra_space = Thyra::tpetraVectorSpace<double>(map);
  const Teuchos::RCP<const Thyra::VectorSpaceBase<double>> space = tpetra_space;
  auto lows = factory.lows_factory()->createOp();
  SolveCounts counts;
  for (int k = 0; k < 5; ++k) {
    const auto matrix = shifted_laplacian(n, -1.0 + 0.02 * k);
    const Teuchos::RCP<const Thyra::LinearOpBase<double>> op =
        Thyra::tpetraLinearOp<double, LocalOrdinal, GlobalOrdinal, Node>(tpetra_space, tpetra_space, matrix);
    Thyra::initializeOp(*factory.lows_factory(), op, lows.ptr());
    auto exact = Teuchos::rcp(new Vector(map)), b = Teuchos::rcp(new Vector(map)), x = Teuchos::rcp(new Vector(map));
    for (std::size_t local = 0; local < map->getNodeNumElements(); ++local)
      exact->replaceLocalValue(local, std::sin(0.01 * map->getGlobalElement(local)) + 1.0);
    matrix->apply(*exact, *b);
    x->putScalar(0.0);
    const auto status = lows->solve(Thyra::NOTRANS, *Thyra::createVector(b, space), Thyra::createVector(x, space).ptr());
    EXPECT_EQ(status.solveStatus, Thyra::SOLVE_STATUS_CONVERGED) << "system " << k;
    x->update(-1.0, *exact, 1.0);
    counts.worst_error = std::max(counts.worst_error, x->normInf() / exact->normInf());
  }
  counts.factorizations = factory.mumps_statistics().factorizations;
  counts.reused = factory.mumps_statistics().reused;
  return counts;
}

}  // namespace

TEST(LinearSolverFactory, EverySolverReachesTheSolutionOfAChangingSequence)
{
  solvers::LinearSolverParameters fresh;   // a double-precision factorization for every system
  fresh.mumps.single_precision = false;
  fresh.refactor = solvers::RefactorRule::lag;
  fresh.lag = 0;
  const auto every = solve_sequence(fresh);
  EXPECT_LT(every.worst_error, 1e-8);
  EXPECT_EQ(every.factorizations, 5);
  EXPECT_EQ(every.reused, 0);

  solvers::LinearSolverParameters lagged = fresh;   // one factorization serves the next four (GMRES on old factors)
  lagged.lag = 4;
  const auto kept = solve_sequence(lagged);
  EXPECT_LT(kept.worst_error, 1e-8);
  EXPECT_EQ(kept.factorizations, 1);
  EXPECT_EQ(kept.reused, 4);

  solvers::LinearSolverParameters double_factors;   // the cost rule with double-precision factors
  double_factors.mumps.single_precision = false;
  const auto cost = solve_sequence(double_factors);
  EXPECT_LT(cost.worst_error, 1e-8);
  EXPECT_EQ(cost.factorizations + cost.reused, 5);
  EXPECT_GE(cost.factorizations, 1);

  // The defaults: single-precision factors, which flexible GMRES refines to double precision's solutions.
  const auto refined = solve_sequence(solvers::LinearSolverParameters{});
  EXPECT_TRUE(solvers::LinearSolverParameters{}.mumps.single_precision);
  EXPECT_LT(refined.worst_error, 1e-8);
  EXPECT_EQ(refined.factorizations + refined.reused, 5);

  solvers::LinearSolverParameters ilu;   // Belos GMRES with Ifpack2 ILU(1): no MUMPS at all
  ilu.type = solvers::LinearSolverType::gmres_ilu;
  const auto iterative = solve_sequence(ilu);
  EXPECT_LT(iterative.worst_error, 1e-6);
  EXPECT_EQ(iterative.factorizations, 0);
}
