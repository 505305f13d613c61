// The laws and element kernels on a GPU backend: every function a kernel reaches is compiled for
// the device and run there on a batch of perturbed elements, and the device's energies, residuals and tangents are
// compared with the host's (the same functions called on the host). Built by scripts/check-device-kernels.sh with
// nvcc against a CUDA-enabled Kokkos; where the machine has no GPU it stops after compiling and linking, says so and
// exits with 77 (skipped); a GPU it cannot use (an NVIDIA driver too old for this CUDA) is a failure, not a skip.
//
// Covered: the Neo-Hookean law in Hex8 and Hex13 (Q1C2) solids, the frictionless Lennard-Jones law on flat and rough
// substrates and the stiction law in Q1C2 contact faces (Quad9), and Q1C1 faces (Quad4). Not covered: the scatter
// into the Tpetra matrix (element_scatter.hpp), which needs a CUDA Tpetra.
#include "contact/contact_face.hpp"
#include "elements/solid_element.hpp"
#include "laws/neo_hookean.hpp"

#include <Kokkos_Core.hpp>

#include <cmath>
#include <cstdio>

namespace {

using namespace spatula;

constexpr int elements_per_kind = 256;
constexpr int kinds = 6;   // hex8, hex13, Q1C2 flat, Q1C2 rough, Q1C2 stiction, Q1C1 flat

// A unit-ish hexahedron (or its bottom face) with node k of element e moved by a smooth, element-dependent amount.
KOKKOS_INLINE_FUNCTION double perturbation(int element, int node, int component)
{
  return 0.04 * ::sin(0.37 * element + 1.3 * node + 2.1 * component);
}

KOKKOS_INLINE_FUNCTION void hex_nodes(int element, double X[13][3], double u[13][3])
{
  const double corners[8][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
  for (int k = 0; k < 8; ++k)
    for (int i = 0; i < 3; ++i) X[k][i] = corners[k][i];
  const int edges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (int m = 0; m < 4; ++m)
    for (int i = 0; i < 3; ++i) X[8 + m][i] = 0.5 * (X[edges[m][0]][i] + X[edges[m][1]][i]);
  for (int i = 0; i < 3; ++i) X[12][i] = 0.25 * (X[0][i] + X[1][i] + X[2][i] + X[3][i]);
  for (int k = 0; k < 13; ++k)
    for (int i = 0; i < 3; ++i) u[k][i] = perturbation(element, k, i);
}

// The bottom face's nodes in Quad9 order, lifted to a gap of about 0.5-1.5 nm above the substrate at z = 0.
KOKKOS_INLINE_FUNCTION void face_nodes(int element, double X[9][3], double u[9][3])
{
  const double at[9][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}, {1, 2}, {0, 1}, {1, 1}};
  for (int k = 0; k < 9; ++k) {
    X[k][0] = at[k][0] + 10.0 * element;   // across the rough substrate's asperities
    X[k][1] = at[k][1];
    X[k][2] = 1.0;
    for (int i = 0; i < 3; ++i) u[k][i] = 10.0 * perturbation(element, k, i) * (i == 2 ? 0.5 : 1.0);
  }
}

// What one element gives: its energy and a weighted sum of its residual and tangent entries (which catches a wrong
// entry anywhere, with weights that differ from entry to entry).
struct Fingerprint {
  double energy = 0.0, residual = 0.0, tangent = 0.0;
};

template <int n>
KOKKOS_INLINE_FUNCTION void fingerprint(double energy, const double r[n], const double (*K)[n], Fingerprint& f)
{
  f.energy = energy;
  f.residual = 0.0;
  f.tangent = 0.0;
  for (int p = 0; p < n; ++p) {
    f.residual += (1.0 + 0.01 * p) * r[p];
    for (int q = 0; q < n; ++q) f.tangent += (1.0 + 0.001 * (p * n + q)) * K[p][q];
  }
}

struct Kernels {
  laws::NeoHookean solid = laws::NeoHookean::from_young(2.0, 0.2);
  contact::FrictionlessIntegrand<contact::FlatSubstrate> flat;
  contact::FrictionlessIntegrand<contact::RoughSubstrate> rough;
  contact::StictionIntegrand stiction;

  Kernels()
  {
    contact::LennardJones law;
    law.hamaker = 0.1;
    law.r0 = 0.4;
    law.r_reg = 0.8 * law.equilibrium_gap();
    law.r_cut = 10.0;
    flat.law = law;
    rough.law = law;
    stiction.law.law = law;
    rough.substrate.base = -4.0;
  }

  KOKKOS_INLINE_FUNCTION Fingerprint operator()(int kind, int element) const
  {
    Fingerprint f;
    if (kind <= 1) {
      double X[13][3], u[13][3], r[39], K[39][39], energy = 0.0;
      hex_nodes(element, X, u);
      if (kind == 0) {
        double X8[8][3], u8[8][3], r8[24], K8[24][24];
        for (int k = 0; k < 8; ++k)
          for (int i = 0; i < 3; ++i) X8[k][i] = X[k][i], u8[k][i] = u[k][i];
        elements::hex8_solid(solid, X8, u8, 2, energy, r8, K8);
        fingerprint<24>(energy, r8, K8, f);
      } else {
        elements::solid_element<elements::Hex13Shape>(solid, X, u, 3, energy, r, K);
        fingerprint<39>(energy, r, K, f);
      }
      return f;
    }
    double X[9][3], u[9][3], r[27], K[27][27];
    face_nodes(element, X, u);
    contact::ContactFaceResult result;
    if (kind == 2) result = contact::contact_face<elements::Quad9Surface>(flat, X, u, 6, r, K);
    if (kind == 3) result = contact::contact_face<elements::Quad9Surface>(rough, X, u, 6, r, K);
    if (kind == 4) result = contact::contact_face<elements::Quad9Surface>(stiction, X, u, 6, r, K);
    if (kind <= 4) {
      fingerprint<27>(result.energy, r, K, f);
      return f;
    }
    double X4[4][3], u4[4][3], r4[12], K4[12][12];
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) X4[k][i] = X[k][i], u4[k][i] = u[k][i];
    result = contact::contact_face<elements::Quad4Surface>(flat, X4, u4, 6, r4, K4);
    fingerprint<12>(result.energy, r4, K4, f);
    return f;
  }
};

}  // namespace

int main(int argc, char** argv)
{
  int devices = 0;
  const cudaError_t found = cudaGetDeviceCount(&devices);
  // No GPU: no device, or no NVIDIA driver at all (the runtime then reports an insufficient driver as well).
  std::FILE* version = std::fopen("/proc/driver/nvidia/version", "r");
  const bool driver = version != nullptr;
  if (version) std::fclose(version);
  if (found == cudaErrorNoDevice || (found == cudaSuccess && devices == 0) ||
      (found == cudaErrorInsufficientDriver && !driver)) {
    std::printf("element_kernels_on_device: compiled and linked for the device; no GPU here to run them on\n");
    return 77;
  }
  if (found != cudaSuccess) {
    std::printf("element_kernels_on_device: the GPU cannot be used: %s\n", cudaGetErrorString(found));
    return 1;
  }
  Kokkos::ScopeGuard guard(argc, argv);
  using Device = Kokkos::DefaultExecutionSpace;
  const int count = kinds * elements_per_kind;
  Kokkos::View<Fingerprint*, Device::memory_space> on_device("spatula: element fingerprints", count);
  const Kernels kernels;
  Kokkos::parallel_for(
      "spatula: element kernels on the device", Kokkos::RangePolicy<Device>(0, count),
      KOKKOS_LAMBDA(int i) { on_device(i) = kernels(i / elements_per_kind, i % elements_per_kind); });
  auto copied = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), on_device);

  const char* names[kinds] = {"hex8 Neo-Hookean", "hex13 Neo-Hookean", "Q1C2 flat", "Q1C2 rough", "Q1C2 stiction",
                              "Q1C1 flat"};
  int failures = 0;
  for (int kind = 0; kind < kinds; ++kind) {
    double worst = 0.0;
    for (int element = 0; element < elements_per_kind; ++element) {
      const Fingerprint host = kernels(kind, element), device = copied(kind * elements_per_kind + element);
      const double pairs[3][2] = {{host.energy, device.energy}, {host.residual, device.residual},
                                  {host.tangent, device.tangent}};
      for (const auto& pair : pairs) {   // a non-finite value on either side, or an element with no energy, fails
        const double difference = std::fabs(pair[0] - pair[1]) / std::fmax(1e-300, std::fabs(pair[0]));
        if (!(difference <= worst)) worst = std::isfinite(pair[0]) && std::isfinite(pair[1]) ? difference : HUGE_VAL;
      }
      if (host.energy == 0.0) worst = HUGE_VAL;
    }
    const bool ok = worst < 1e-11;
    failures += !ok;
    std::printf("%-18s %d elements: largest relative difference device/host %.2e %s\n", names[kind],
                elements_per_kind, worst, ok ? "ok" : "FAILED (above 1e-11)");
  }
  return failures ? 1 : 0;
}
