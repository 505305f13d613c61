#pragma once
// Device-side gather and scatter between element arrays and the distributed system, shared by every element
// kernel (bulk solids and contact faces). A nodal displacement component is a free unknown, fixed (zero), follows
// the rigid end face (u(alpha, w), rigid_face.hpp) or is dependent (the mean of two corner nodes, Q1C2 edges
// shared with plain elements). The scatter applies the chain rule with T = du/dq, q the rank's local unknowns:
//
//   r_q  = T^T r_e,     K_qq = T^T K_e T + sum_rigid r_e . d2u/dalpha2 (alpha-alpha entry).
//
// Rows and columns of prescribed masters are left out of the matrix (they get an identity row elsewhere); their
// residual is kept: it is the reaction.
#include "discretization/rigid_face.hpp"
#include "discretization/tpetra_types.hpp"

namespace spatula::discretization {

constexpr int fixed_component = -1;
constexpr int rigid_component = -2;
constexpr int dependent_component = -3;

struct ElementScatter {
  using local_matrix_type = CrsMatrix::local_matrix_device_type;
  using residual_view_type = MultiVector::dual_view_type::t_dev;
  using state_view_type = MultiVector::dual_view_type::t_dev_const;

  local_matrix_type matrix;
  residual_view_type residual;
  residual_view_type coupling;   // column m: d f / d(master m) of prescribed masters (with the matrix)
  state_view_type state;                                   // owned + shared values of the current state
  Kokkos::View<const int*, device_type> column_of;          // owned+shared local id -> local column
  Kokkos::View<const int* [3], device_type> node_unknown;   // local unknown or one of the kinds above
  Kokkos::View<const double* [3], device_type> node_offset;   // X - c of rigid nodes
  Kokkos::View<const int* [2], device_type> node_parent;      // corners of dependent nodes (local ids)
  int master_unknown[master_count] = {-1, -1, -1};         // local ids of the masters (-1: not on this rank)
  bool master_prescribed[master_count] = {true, true, true};
  double masters[master_count] = {0.0, 0.0, 0.0};          // alpha, w, s
  RigidFaceDirections directions;
  bool with_residual = true, with_matrix = true;
  // Tangent entries whose column is not in the row's graph (summed atomically; the assembly checks it is zero: the
  // graph is built from the same element connectivity, so an entry can only go missing through a bug).
  Kokkos::View<int[1], device_type> dropped;

  KOKKOS_INLINE_FUNCTION RigidFaceMotion motion(int node) const
  {
    const double d[3] = {node_offset(node, 0), node_offset(node, 1), node_offset(node, 2)};
    return rigid_face_motion(masters, d, directions);
  }

  KOKKOS_INLINE_FUNCTION double component(int node, int i) const
  {
    const int kind = node_unknown(node, i);
    if (kind >= 0) return state(kind, 0);
    if (kind == rigid_component) return motion(node).u[i];
    if (kind == dependent_component) {
      double sum = 0.0;
      for (int p = 0; p < 2; ++p) {
        const int parent = node_unknown(node_parent(node, p), i);
        if (parent >= 0) sum += 0.5 * state(parent, 0);
      }
      return sum;
    }
    return 0.0;
  }

  KOKKOS_INLINE_FUNCTION void displacement(int node, double u[3]) const
  {
    for (int i = 0; i < 3; ++i) u[i] = component(node, i);
  }

  // Adds an element's residual r[3N] and (if with_matrix) tangent K[3N][3N] for its N local nodes.
  template <int N>
  KOKKOS_INLINE_FUNCTION void add(const int nodes[N], const double r[3 * N], const double (*K)[3 * N]) const
  {
    constexpr int dofs = 3 * N, most = 3 * N + master_count, targets = 3;
    int unknowns[most];    // distinct local unknowns touched
    int count = 0;
    int target_count[dofs];              // per element dof: how many unknowns it depends on (0 to 3),
    int target[dofs][targets];           // their positions in `unknowns`
    double coefficient[dofs][targets];   // and du/dq
    double second[dofs];   // d2u/dalpha2 of rigid components
    int alpha_position = -1;
    auto position_of = [&](int unknown) {
      for (int k = 0; k < count; ++k)
        if (unknowns[k] == unknown) return k;
      unknowns[count] = unknown;
      return count++;
    };
    for (int p = 0; p < dofs; ++p) {
      const int node = nodes[p / 3], i = p % 3;
      const int kind = node_unknown(node, i);
      int& n = target_count[p];
      n = 0;
      second[p] = 0.0;
      if (kind >= 0) {
        target[p][n] = position_of(kind);
        coefficient[p][n++] = 1.0;
      } else if (kind == rigid_component) {
        const RigidFaceMotion m = motion(node);
        if (i != 1) {   // the face moves in the X-Z plane only
          target[p][n] = alpha_position = position_of(master_unknown[0]);
          coefficient[p][n++] = m.du_dalpha[i];
          second[p] = m.d2u_dalpha2[i];
          target[p][n] = position_of(master_unknown[1]);
          coefficient[p][n++] = directions.lift[i];
          target[p][n] = position_of(master_unknown[2]);
          coefficient[p][n++] = directions.slide[i];
        }
      } else if (kind == dependent_component) {
        for (int t = 0; t < 2; ++t) {
          const int parent = node_unknown(node_parent(node, t), i);
          if (parent < 0) continue;
          target[p][n] = position_of(parent);
          coefficient[p][n++] = 0.5;
        }
      }
    }
    if (with_residual)
      for (int p = 0; p < dofs; ++p)
        for (int t = 0; t < target_count[p]; ++t)
          Kokkos::atomic_add(&residual(unknowns[target[p][t]], 0), coefficient[p][t] * r[p]);
    if (!with_matrix) return;

    double reduced[most][most];
    for (int a = 0; a < count; ++a)
      for (int b = 0; b < count; ++b) reduced[a][b] = 0.0;
    for (int p = 0; p < dofs; ++p)
      for (int s = 0; s < target_count[p]; ++s)
        for (int q = 0; q < dofs; ++q)
          for (int t = 0; t < target_count[q]; ++t)
            reduced[target[p][s]][target[q][t]] += coefficient[p][s] * coefficient[q][t] * K[p][q];
    if (alpha_position >= 0)
      for (int p = 0; p < dofs; ++p) reduced[alpha_position][alpha_position] += r[p] * second[p];

    auto prescribed = [&](int unknown) {
      for (int m = 0; m < master_count; ++m)
        if (unknown == master_unknown[m] && master_prescribed[m]) return true;
      return false;
    };
    // The element's matrix columns in ascending order (every row of it has the same ones), so that sumIntoValues
    // finds them in the row's sorted column indices by a forward search from the last one found.
    int order[most], columns[most];
    int free_count = 0;
    for (int b = 0; b < count; ++b) {
      if (prescribed(unknowns[b])) continue;
      const int column = column_of(unknowns[b]);
      int k = free_count++;
      for (; k > 0 && columns[k - 1] > column; --k) {
        columns[k] = columns[k - 1];
        order[k] = order[k - 1];
      }
      columns[k] = column;
      order[k] = b;
    }
    double values[most];
    for (int a = 0; a < count; ++a) {
      if (prescribed(unknowns[a])) continue;
      for (int b = 0; b < count; ++b)   // the load column of a prescribed master: kept aside (df/dp)
        for (int m = 0; m < master_count; ++m)
          if (unknowns[b] == master_unknown[m] && master_prescribed[m])
            Kokkos::atomic_add(&coupling(unknowns[a], m), reduced[a][b]);
      for (int j = 0; j < free_count; ++j) values[j] = reduced[a][order[j]];
      const int added = matrix.sumIntoValues(unknowns[a], columns, free_count, values, true, true);
      if (added != free_count) Kokkos::atomic_add(&dropped(0), free_count - added);
    }
  }
};

}  // namespace spatula::discretization
