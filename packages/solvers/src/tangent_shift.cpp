#include "solvers/tangent_shift.hpp"

#include <Kokkos_Core.hpp>

namespace spatula::solvers {

namespace {

using discretization::CrsMatrix;
using discretization::master_count;

// One owned row per work item: its diagonal entry += value, unless the row is one of `skip`. A named functor, as the
// assembly's kernels are (a CUDA build cannot take an extended lambda from every context).
struct ShiftDiagonal {
  CrsMatrix::local_matrix_device_type matrix;
  CrsMatrix::map_type::local_map_type rows, columns;
  double value;
  int skip[master_count];

  KOKKOS_INLINE_FUNCTION void operator()(const int row) const
  {
    for (int m = 0; m < master_count; ++m)
      if (row == skip[m]) return;
    const int column = columns.getLocalElement(rows.getGlobalElement(row));
    matrix.sumIntoValues(row, &column, 1, &value, false, true);
  }
};

}  // namespace

void shift_tangent(discretization::DiscreteSystem& system, double eta)
{
  auto& matrix = *system.jacobian();
  const auto& row_map = *matrix.getRowMap();
  ShiftDiagonal shift{matrix.getLocalMatrixDevice(), row_map.getLocalMap(), matrix.getColMap()->getLocalMap(), eta, {}};
  for (int m = 0; m < master_count; ++m)
    shift.skip[m] = system.control().prescribed[m] ? row_map.getLocalElement(system.layout().masters[m]) : -1;
  const int rows = static_cast<int>(row_map.getNodeNumElements());
  Kokkos::parallel_for("spatula: descent's proximal shift",
                       Kokkos::RangePolicy<discretization::execution_space>(0, rows), shift);
  Kokkos::fence();
}

}  // namespace spatula::solvers
