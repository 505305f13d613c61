#include "analysis/tangent_spectrum.hpp"

#include <cmath>

namespace spatula::analysis {

NearestEigenvalue nearest_eigenvalue(const discretization::CrsMatrix& tangent, solvers::MumpsSolver& solver,
                                     int iterations, double mean_diagonal)
{
  using discretization::Vector;
  const auto map = tangent.getRowMap();
  solver.factor(tangent);
  NearestEigenvalue result;
  result.negative_pivots = solver.statistics().negative_pivots;
  Vector y(map), z(map), product(map);
  {
    auto values = y.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (std::size_t i = 0; i < values.extent(0); ++i) {   // a smooth, sign-changing start, by global number
      const auto global = static_cast<double>(map->getGlobalElement(static_cast<discretization::LocalOrdinal>(i)));
      values(i, 0) = 1.0 + 0.5 * std::sin(0.7 * global);
    }
  }
  y.scale(1.0 / y.norm2());
  for (int k = 0; k < iterations; ++k) {
    solver.apply(y, z);
    y.update(1.0 / z.norm2(), z, 0.0);
  }
  tangent.apply(y, product);
  result.value = y.dot(product);
  result.relative = mean_diagonal != 0.0 ? result.value / mean_diagonal : 0.0;
  product.update(-result.value, y, 1.0);
  result.residual = result.value != 0.0 ? product.norm2() / std::abs(result.value) : 0.0;
  // The participation ratio from the squares and fourth powers of y's entries.
  Vector squares(map);
  squares.elementWiseMultiply(1.0, y, y, 0.0);
  const double fourth = squares.dot(squares);
  result.participation = fourth > 0.0 ? 1.0 / (static_cast<double>(map->getGlobalNumElements()) * fourth) : 0.0;
  return result;
}

}  // namespace spatula::analysis
