// The eigenvalue nearest zero by inverse iteration, on a matrix with known eigenpairs: tridiag(-1, 2, -1) - shift I,
// eigenvalues 2 - 2 cos(k pi / (n + 1)) - shift with sine modes, on one rank or two.
#include "analysis/tangent_spectrum.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using namespace spatula;
using discretization::CrsMatrix;
using discretization::GlobalOrdinal;
using discretization::Map;

constexpr double pi = 3.14159265358979323846;
constexpr GlobalOrdinal n = 50;

Teuchos::RCP<CrsMatrix> shifted_laplacian(double shift)
{
  auto map = Teuchos::rcp(new Map(n, 0, Teuchos::DefaultComm<int>::getComm()));
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

double eigenvalue(int k) { return 2.0 - 2.0 * std::cos(k * pi / (n + 1)); }

TEST(TangentSpectrum, NearestEigenvalueAndItsSineModesParticipation)
{
  const auto matrix = shifted_laplacian(0.0);
  solvers::MumpsSolver solver(matrix->getRowMap(), solvers::MumpsParameters{});
  const auto nearest = analysis::nearest_eigenvalue(*matrix, solver, 30, 2.0);
  EXPECT_NEAR(nearest.value, eigenvalue(1), 1e-12);
  EXPECT_NEAR(nearest.relative, eigenvalue(1) / 2.0, 1e-12);
  EXPECT_LT(nearest.residual, 1e-6);
  EXPECT_EQ(nearest.negative_pivots, 0);
  // sin(i pi / (n + 1)) normalized: sum y^4 = 3 / (2 (n + 1)), so the participation ratio is 2 (n + 1) / (3 n).
  EXPECT_NEAR(nearest.participation, 2.0 * (n + 1) / (3.0 * n), 1e-6);
}

TEST(TangentSpectrum, PastTheFirstEigenvalueTheNearestIsNegativeWithOneNegativePivot)
{
  const double shift = 0.5 * (eigenvalue(1) + eigenvalue(2)) - 0.2 * (eigenvalue(2) - eigenvalue(1));
  const auto matrix = shifted_laplacian(shift);
  solvers::MumpsSolver solver(matrix->getRowMap(), solvers::MumpsParameters{});
  const auto nearest = analysis::nearest_eigenvalue(*matrix, solver, 60, 2.0);
  EXPECT_NEAR(nearest.value, eigenvalue(1) - shift, 1e-10);
  EXPECT_EQ(nearest.negative_pivots, 1);
}

}  // namespace
