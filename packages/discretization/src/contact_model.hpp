#pragma once
// The adhesion contribution to the system: the pad's contact faces integrated with a law and a substrate.
// DiscreteSystem calls `assemble` with this rank's faces and the scatter; IntegrandContactModel<Integrand> is the
// implementation for any device integrand (frictionless or stiction, flat or rough: see packages/contact, whose
// registry turns the XML choice into one of these).
#include "elements/contact_face.hpp"
#include "discretization/element_scatter.hpp"

#include <memory>
#include <string>

namespace spatula::discretization {

// This rank's contact faces on the device (local node ids; Quad4 faces use the first 4 columns).
struct ContactFaceViews {
  Kokkos::View<const int* [9], device_type> nodes;
  Kokkos::View<const double*, device_type> areas;      // undeformed area of each face
  Kokkos::View<const double* [3], device_type> coordinates;   // reference positions of the local nodes
  Kokkos::View<const double* [3], device_type> anchors;       // where the stiction law measures travel from
  int face_nodes = 4;
  int count = 0;
};

struct ContactTotals {
  double energy = 0.0;       // Pi_c of this rank's faces [nN nm]
  int active_faces = 0;      // faces integrated (some point within the cut-off)
  int skipped_faces = 0;     // faces certainly beyond the cut-off: not integrated
  int active_points = 0;     // quadrature points within the cut-off
};

class ContactModel {
public:
  virtual ~ContactModel() = default;
  virtual std::string description() const = 0;
  virtual double work_of_adhesion() const = 0;   // w_adh = -phi(r_eq) of the law [nN/nm]
  virtual int quadrature_order() const = 0;
  virtual ContactTotals assemble(const ContactFaceViews& faces, const ElementScatter& scatter) const = 0;
};

namespace detail {

// One face per work item; sums[0] energy, sums[1] integrated faces, sums[2] active points. An array sum: Kokkos'
// own init (zeros) and join (+=) serve, so the kernel declares neither (Kokkos 4 rejects the volatile join that
// Kokkos 3 asked for).
template <class Surface, class Integrand>
struct ContactKernel {
  using value_type = double[];
  unsigned value_count = 3;
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
    // Skip a face whose every point is beyond the cut-off (with a margin for the quadratic interpolation).
    if (skip_distant && nearest - 0.5 * (farthest - nearest) > integrand.cut_off()) {
      double phi, gradient[3];
      double x_far[3] = {0.0, 0.0, 1e300};
      integrand.evaluate(A[0], x_far, phi, gradient, nullptr);
      sums[0] += phi * faces.areas(face);
      return;
    }
    double r[3 * n], K[3 * n][3 * n];
    const auto result = elements::contact_face<Surface>(integrand, X, A, u, order, r,
                                                               scatter.with_matrix ? K : nullptr);
    sums[0] += result.energy;
    sums[1] += 1.0;
    sums[2] += result.active_points;
    if (result.active_points > 0) scatter.add<n>(nodes, r, K);
  }
};

}  // namespace detail

template <class Integrand>
class IntegrandContactModel : public ContactModel {
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

  ContactTotals assemble(const ContactFaceViews& faces, const ElementScatter& scatter) const override
  {
    double sums[3] = {0.0, 0.0, 0.0};
    const auto policy = Kokkos::RangePolicy<execution_space>(0, faces.count);
    if (faces.face_nodes == 9) {
      detail::ContactKernel<elements::Quad9Surface, Integrand> kernel{3, scatter, faces, integrand_, order_, skip_distant_};
      Kokkos::parallel_reduce("spatula: contact Q1C2 faces", policy, kernel, sums);
    } else {
      detail::ContactKernel<elements::Quad4Surface, Integrand> kernel{3, scatter, faces, integrand_, order_, skip_distant_};
      Kokkos::parallel_reduce("spatula: contact Q1C1 faces", policy, kernel, sums);
    }
    ContactTotals totals;
    totals.energy = sums[0];
    totals.active_faces = static_cast<int>(sums[1]);
    totals.skipped_faces = faces.count - totals.active_faces;
    totals.active_points = static_cast<int>(sums[2]);
    return totals;
  }

private:
  Integrand integrand_;
  int order_;
  std::string description_;
  double work_;
  bool skip_distant_;
};

}  // namespace spatula::discretization
