#pragma once
// The bulk solid's element kernel: one Hex8 or Hex13 element per work item of a Kokkos parallel_reduce. It gathers
// the element's nodes and displacements, evaluates the element with a hyperelastic law (elements/solid_element.hpp; the
// law a template parameter, laws::NeoHookean by default) on stack
// arrays, reduces its energy and scatters its residual and tangent into the global system (element_scatter.hpp); an
// inverted element is reported (atomic max of its id + 1), not assembled.
#include "discretization/element_scatter.hpp"
#include "elements/solid_element.hpp"
#include "laws/neo_hookean.hpp"

#include <Kokkos_Core.hpp>

#include <cstdint>

namespace spatula::discretization {

// Bulk solid: one element per work item (Hex8 or Hex13); reduces the energy, reports an inverted element.
template <class Shape, class Law = laws::NeoHookean>
struct SolidKernel {
  ElementScatter scatter;
  DeviceView<const int**> element_nodes;
  DeviceView<const std::int64_t*> element_ids;
  DeviceView<const double* [3]> coordinates;
  DeviceView<std::int64_t[1]> inverted;   // global id + 1 of an inverted element, 0 if none
  Law law;
  int order = 2;

  KOKKOS_INLINE_FUNCTION void operator()(const int element, double& energy) const
  {
    constexpr int n = Shape::nodes;
    int nodes[n];
    double X[n][3], u[n][3];
    for (int a = 0; a < n; ++a) {
      nodes[a] = element_nodes(element, a);
      for (int i = 0; i < 3; ++i) X[a][i] = coordinates(nodes[a], i);
      scatter.displacement(nodes[a], u[a]);
    }
    double element_energy, r[3 * n], K[3 * n][3 * n];
    const auto status =
        elements::solid_element<Shape>(law, X, u, order, element_energy, r, scatter.with_matrix ? K : nullptr);
    if (status != elements::ElementStatus::ok) {
      Kokkos::atomic_fetch_max(&inverted(0), element_ids(element) + 1);
      return;
    }
    energy += element_energy;
    scatter.add<n>(nodes, r, K);
  }
};

}  // namespace spatula::discretization
