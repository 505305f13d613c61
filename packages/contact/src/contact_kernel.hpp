#pragma once
// The contact faces' device kernel: one face per work item of a Kokkos parallel_reduce, integrated by
// contact_face.hpp with a law x substrate integrand and scattered into the global system; faces whose every point is
// beyond the cut-off are skipped. IntegrandContactModel<Integrand> is the discretization::ContactModel for any such
// integrand (the registry, contact_registry.cpp, makes one per law and substrate).
#include "contact/contact_face.hpp"
#include "discretization/contact_model.hpp"

#include <memory>
#include <string>

namespace spatula::contact {

using discretization::ContactFaceViews;
using discretization::ContactTotals;
using discretization::ElementScatter;
using discretization::execution_space;

namespace detail {

// One face per work item; sums[0] energy, sums[1] integrated faces, sums[2] active points, sums[3] dissipated
// energy (a law with state). An array sum: Kokkos'
// own init (zeros) and join (+=) serve, so the kernel declares neither (Kokkos 4 rejects the volatile join that
// Kokkos 3 asked for).
template <class Surface, class Integrand>
struct ContactKernel {
  using value_type = double[];
  unsigned value_count = 4;
  ElementScatter scatter;
  ContactFaceViews faces;
  Integrand integrand;
  int order = 4;
  bool skip_distant = true;

  KOKKOS_INLINE_FUNCTION void operator()(const int face, value_type sums) const
  {
    constexpr int n = Surface::nodes;
    int nodes[n];
    double X[n][3], A[n][3], u[n][3];
    double nearest = 1e300, farthest = -1e300;
    for (int k = 0; k < n; ++k) {
      nodes[k] = faces.nodes(face, k);
      scatter.displacement(nodes[k], u[k]);
      double x[3];
      for (int i = 0; i < 3; ++i) {
        X[k][i] = faces.coordinates(nodes[k], i);
        A[k][i] = faces.anchors(nodes[k], i);
        x[i] = X[k][i] + u[k][i];
      }
      const double bound = integrand.far_bound(x);
      nearest = bound < nearest ? bound : nearest;
      farthest = bound > farthest ? bound : farthest;
    }
    constexpr int kept = HistorySize<Integrand>::value;
    const int stride = order * order * kept;
    const double* history = kept > 0 ? faces.history.data() + face * stride : nullptr;
    double* trial = kept > 0 ? faces.trial_history.data() + face * stride : nullptr;
    // Skip a face whose every point is beyond the cut-off (with a margin for the quadratic interpolation); a law
    // with state keeps the face's history there.
    if (skip_distant && nearest - 0.5 * (farthest - nearest) > integrand.cut_off()) {
      double phi, gradient[3];
      double x_far[3] = {0.0, 0.0, 1e300};
      integrand.evaluate(A[0], x_far, phi, gradient, nullptr);
      sums[0] += phi * faces.areas(face);
      if constexpr (kept > 0) {
        for (int k = 0; k < stride; ++k) trial[k] = history[k];
        for (int a = 0; a < order; ++a)
          for (int b = 0; b < order; ++b)
            sums[3] += Integrand::dissipated(history + (a * order + b) * kept) *
                       FacePoint<Surface>(order, a, b, X, A).dA;
      }
      return;
    }
    double r[3 * n], K[3 * n][3 * n];
    const auto result = contact_face<Surface>(integrand, X, A, u, order, r, scatter.with_matrix ? K : nullptr,
                                              history, trial);
    sums[0] += result.energy;
    sums[1] += 1.0;
    sums[2] += result.active_points;
    sums[3] += result.dissipated;
    if (result.active_points > 0) scatter.add<n>(nodes, r, K);
  }
};

// A face's nodes (local ids), reference coordinates, anchors and displacements in two states.
template <int n>
struct FaceStates {
  int nodes[n];
  double X[n][3], A[n][3], u_from[n][3], u_to[n][3];

  KOKKOS_INLINE_FUNCTION FaceStates(const ContactFaceViews& faces, int face, const ElementScatter& from,
                                    const ElementScatter& to)
  {
    for (int k = 0; k < n; ++k) {
      nodes[k] = faces.nodes(face, k);
      from.displacement(nodes[k], u_from[k]);
      to.displacement(nodes[k], u_to[k]);
      for (int i = 0; i < 3; ++i) {
        X[k][i] = faces.coordinates(nodes[k], i);
        A[k][i] = faces.anchors(nodes[k], i);
      }
    }
  }
};

// One face per work item: face_gap_changes between the displacements of two scatters.
template <class Surface, class Integrand>
struct GapChangeKernel {
  using value_type = double[];
  unsigned value_count = gap_change_sums;
  ElementScatter from, to;
  ContactFaceViews faces;
  Integrand integrand;
  int order = 4;
  double large = 0.0;

  KOKKOS_INLINE_FUNCTION void operator()(const int face, value_type sums) const
  {
    const FaceStates<Surface::nodes> states(faces, face, from, to);
    face_gap_changes<Surface>(integrand, states.X, states.A, states.u_from, states.u_to, order, large, sums);
  }
};

// One face per work item: face_gap_limit between the displacements of two scatters, its row scattered into the
// residual of `from`.
template <class Surface, class Integrand>
struct GapLimitKernel {
  using value_type = double[];
  unsigned value_count = gap_limit_sums;
  ElementScatter from, to;
  ContactFaceViews faces;
  Integrand integrand;
  int order = 4;
  double limit = 0.0;

  KOKKOS_INLINE_FUNCTION void operator()(const int face, value_type sums) const
  {
    constexpr int n = Surface::nodes;
    const FaceStates<n> states(faces, face, from, to);
    double r[3 * n], face_sums[gap_limit_sums] = {0.0, 0.0};
    face_gap_limit<Surface>(integrand, states.X, states.A, states.u_from, states.u_to, order, limit, r, face_sums);
    if (face_sums[0] == 0.0) return;
    for (int k = 0; k < gap_limit_sums; ++k) sums[k] += face_sums[k];
    from.add<n>(states.nodes, r, nullptr);
  }
};

}  // namespace detail

template <class Integrand>
class IntegrandContactModel : public discretization::ContactModel {
public:
  IntegrandContactModel(Integrand integrand, int order, std::string description, double work_of_adhesion,
                        bool skip_distant_faces = true)
      : integrand_(integrand), order_(order), description_(std::move(description)), work_(work_of_adhesion),
        skip_distant_(skip_distant_faces)
  {
  }
  std::string description() const override { return description_; }
  double work_of_adhesion() const override { return work_; }
  int quadrature_order() const override { return order_; }
  int history_size() const override { return HistorySize<Integrand>::value; }
  int dissipated_index() const override { return DissipatedIndex<Integrand>::value; }
  bool holds_tangentially() const override { return Tangential<Integrand>::value; }
  bool symmetric() const override { return symmetric_tangent(integrand_); }
  std::shared_ptr<const ContactModel> descent_law() const override
  {
    if constexpr (DeclaresDescent<Integrand>::value) {
      if (integrand_.descends_on_another_energy())
        return std::make_shared<IntegrandContactModel<Integrand>>(
            integrand_.descent_integrand(), order_, description_ + " (its jumps descend on the frozen limit's energy)",
            work_, skip_distant_);
    }
    return nullptr;
  }

  ContactTotals assemble(const ContactFaceViews& faces, const ElementScatter& scatter) const override
  {
    double sums[4] = {0.0, 0.0, 0.0, 0.0};
    const auto policy = Kokkos::RangePolicy<execution_space>(0, faces.count);
    if (faces.face_nodes == 9) {
      detail::ContactKernel<elements::Quad9Surface, Integrand> kernel{4, scatter, faces, integrand_, order_, skip_distant_};
      Kokkos::parallel_reduce("spatula: contact Q1C2 faces", policy, kernel, sums);
    } else {
      detail::ContactKernel<elements::Quad4Surface, Integrand> kernel{4, scatter, faces, integrand_, order_, skip_distant_};
      Kokkos::parallel_reduce("spatula: contact Q1C1 faces", policy, kernel, sums);
    }
    ContactTotals totals;
    totals.energy = sums[0];
    totals.active_faces = static_cast<int>(sums[1]);
    totals.skipped_faces = faces.count - totals.active_faces;
    totals.active_points = static_cast<int>(sums[2]);
    totals.dissipated = sums[3];
    return totals;
  }

  std::array<double, gap_change_sums> gap_changes(const ContactFaceViews& faces, const ElementScatter& from,
                                    const ElementScatter& to, double fraction) const override
  {
    std::array<double, gap_change_sums> sums{};
    const auto policy = Kokkos::RangePolicy<execution_space>(0, faces.count);
    const double large = fraction * integrand_.range();
    if (faces.face_nodes == 9) {
      detail::GapChangeKernel<elements::Quad9Surface, Integrand> kernel{gap_change_sums, from, to, faces, integrand_, order_, large};
      Kokkos::parallel_reduce("spatula: contact Q1C2 gap changes", policy, kernel, sums.data());
    } else {
      detail::GapChangeKernel<elements::Quad4Surface, Integrand> kernel{gap_change_sums, from, to, faces, integrand_, order_, large};
      Kokkos::parallel_reduce("spatula: contact Q1C1 gap changes", policy, kernel, sums.data());
    }
    return sums;
  }

  std::array<double, gap_limit_sums> gap_limit(const ContactFaceViews& faces, const ElementScatter& from,
                                                const ElementScatter& to, double beyond_inflection) const override
  {
    std::array<double, gap_limit_sums> sums{};
    const auto policy = Kokkos::RangePolicy<execution_space>(0, faces.count);
    const double limit = integrand_.inflection() + beyond_inflection;
    if (faces.face_nodes == 9) {
      detail::GapLimitKernel<elements::Quad9Surface, Integrand> kernel{gap_limit_sums, from, to, faces, integrand_, order_, limit};
      Kokkos::parallel_reduce("spatula: contact Q1C2 gap limit", policy, kernel, sums.data());
    } else {
      detail::GapLimitKernel<elements::Quad4Surface, Integrand> kernel{gap_limit_sums, from, to, faces, integrand_, order_, limit};
      Kokkos::parallel_reduce("spatula: contact Q1C1 gap limit", policy, kernel, sums.data());
    }
    return sums;
  }

private:
  Integrand integrand_;
  int order_;
  std::string description_;
  double work_;
  bool skip_distant_;
};

}  // namespace spatula::contact
