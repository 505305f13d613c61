#pragma once
// Device-side gather and scatter between element arrays and the distributed system, shared by every element
// kernel (bulk solid now, contact faces later). A nodal displacement component is either a free unknown, fixed
// (zero), or follows the rigid end face; the scatter applies the chain rule u(alpha, w) for the latter:
//
//   r_q  = T^T r_e,     K_qq = T^T K_e T + sum_rigid r_e . d2u/dalpha2 (alpha-alpha entry),
//
// where T = du/dq maps element dofs to the rank's local unknowns q. Rows and columns of prescribed masters are
// left out of the matrix (they get an identity row elsewhere); their residual is kept: it is the reaction.
#include "rigid_face.hpp"
#include "tpetra_types.hpp"

namespace spatula::discretization {

constexpr int fixed_component = -1;
constexpr int rigid_component = -2;

struct ElementScatter {
  using local_matrix_type = CrsMatrix::local_matrix_device_type;
  using residual_view_type = MultiVector::dual_view_type::t_dev;
  using state_view_type = MultiVector::dual_view_type::t_dev_const;

  local_matrix_type matrix;
  residual_view_type residual;
  state_view_type state;                                   // owned + shared values of the current state
  Kokkos::View<const int*, device_type> column_of;          // owned+shared local id -> local column
  Kokkos::View<const int* [3], device_type> node_unknown;   // local unknown, fixed_component or rigid_component
  Kokkos::View<const double* [3], device_type> node_offset;   // X - c of rigid nodes
  int master_unknown[master_count] = {-1, -1};             // local ids of the masters (-1: not on this rank)
  bool master_prescribed[master_count] = {true, true};
  double alpha = 0.0, lift = 0.0;
  bool with_residual = true, with_matrix = true;

  KOKKOS_INLINE_FUNCTION void displacement(int node, double u[3]) const
  {
    if (node_unknown(node, 0) == rigid_component) {
      const double d[3] = {node_offset(node, 0), node_offset(node, 1), node_offset(node, 2)};
      const RigidFaceMotion motion = rigid_face_motion(alpha, lift, d);
      for (int i = 0; i < 3; ++i) u[i] = motion.u[i];
      return;
    }
    for (int i = 0; i < 3; ++i) {
      const int unknown = node_unknown(node, i);
      u[i] = unknown >= 0 ? state(unknown, 0) : 0.0;
    }
  }

  // Adds an element's residual r[3N] and (if with_matrix) tangent K[3N][3N] for its N local nodes.
  template <int N>
  KOKKOS_INLINE_FUNCTION void add(const int nodes[N], const double r[3 * N], const double (*K)[3 * N]) const
  {
    constexpr int dofs = 3 * N, most = 3 * N + master_count;
    int unknowns[most];    // distinct local unknowns touched
    int count = 0;
    int target[dofs][2];   // per element dof: positions in `unknowns` (or -1)
    double coefficient[dofs][2];
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
      target[p][0] = target[p][1] = -1;
      second[p] = 0.0;
      if (kind >= 0) {
        target[p][0] = position_of(kind);
        coefficient[p][0] = 1.0;
      } else if (kind == rigid_component) {
        const double d[3] = {node_offset(node, 0), node_offset(node, 1), node_offset(node, 2)};
        const RigidFaceMotion motion = rigid_face_motion(alpha, lift, d);
        if (i != 1) {
          target[p][0] = alpha_position = position_of(master_unknown[0]);
          coefficient[p][0] = motion.du_dalpha[i];
          second[p] = motion.d2u_dalpha2[i];
        }
        if (i == 2) {
          target[p][1] = position_of(master_unknown[1]);
          coefficient[p][1] = 1.0;
        }
      }
    }
    if (with_residual)
      for (int p = 0; p < dofs; ++p)
        for (int t = 0; t < 2; ++t)
          if (target[p][t] >= 0)
            Kokkos::atomic_add(&residual(unknowns[target[p][t]], 0), coefficient[p][t] * r[p]);
    if (!with_matrix) return;

    double reduced[most][most];
    for (int a = 0; a < count; ++a)
      for (int b = 0; b < count; ++b) reduced[a][b] = 0.0;
    for (int p = 0; p < dofs; ++p)
      for (int s = 0; s < 2; ++s) {
        if (target[p][s] < 0) continue;
        for (int q = 0; q < dofs; ++q)
          for (int t = 0; t < 2; ++t)
            if (target[q][t] >= 0)
              reduced[target[p][s]][target[q][t]] += coefficient[p][s] * coefficient[q][t] * K[p][q];
      }
    if (alpha_position >= 0)
      for (int p = 0; p < dofs; ++p) reduced[alpha_position][alpha_position] += r[p] * second[p];

    auto prescribed = [&](int unknown) {
      return (unknown == master_unknown[0] && master_prescribed[0]) ||
             (unknown == master_unknown[1] && master_prescribed[1]);
    };
    int columns[most];
    double values[most];
    for (int a = 0; a < count; ++a) {
      if (prescribed(unknowns[a])) continue;
      int n = 0;
      for (int b = 0; b < count; ++b) {
        if (prescribed(unknowns[b])) continue;
        columns[n] = column_of(unknowns[b]);
        values[n++] = reduced[a][b];
      }
      matrix.sumIntoValues(unknowns[a], columns, n, values, false, true);
    }
  }
};

}  // namespace spatula::discretization
