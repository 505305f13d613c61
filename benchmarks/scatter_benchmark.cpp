// Atomics against colouring for the bulk solid's scatter: the spatula's Hex8 elements on a level's mesh,
// each evaluated by the solid element kernel (elements/solid_element.hpp, as discretization/solid_kernel.hpp does) and
// added into a KokkosSparse matrix and a residual View in one of two ways:
//   atomic:   one launch over all elements, every add atomic (sumIntoValues with force_atomic, atomic_add), as the
//             project's ElementScatter does;
//   coloured: elements greedily coloured so that no two of a colour share a node, one launch per colour, plain adds.
// Every node's three components are unknowns here (no end face, no masters, no enrichment): the scatter's memory
// traffic and conflicts without the rigid face's extra columns. Run with KOKKOS_NUM_THREADS=1, 2, ... on a threaded
// Kokkos (scripts/build-trilinos.sh); on the Serial backend both run on one thread.
//
//   scatter_benchmark <coarse|medium|fine> [repetitions]
//
// Prints one CSV line: level, backend, threads, elements, colours, the median seconds of one residual + tangent
// assembly each way, elements per second each way, and the largest difference between the two matrices relative to
// the largest entry (rounding: the additions happen in another order).
#include "discretization/tpetra_types.hpp"
#include "elements/solid_element.hpp"
#include "laws/neo_hookean.hpp"
#include "mesh/spatula_mesher.hpp"

#include <Kokkos_Core.hpp>
#include <KokkosSparse_CrsMatrix.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <set>
#include <vector>

using namespace spatula;
using device_type = discretization::device_type;
using execution_space = discretization::execution_space;
using LocalMatrix = KokkosSparse::CrsMatrix<double, int, device_type>;

namespace {

template <bool atomic>
struct ScatterKernel {
  LocalMatrix matrix;
  Kokkos::View<double*, device_type> residual;
  Kokkos::View<const int* [8], device_type> element_nodes;
  Kokkos::View<const double* [3], device_type> coordinates, displacements;
  Kokkos::View<const int*, device_type> elements;   // the elements of this launch (all, or one colour)
  laws::NeoHookean law;

  KOKKOS_INLINE_FUNCTION void operator()(const int k, double& energy) const
  {
    const int element = elements(k);
    int nodes[8];
    double X[8][3], u[8][3];
    for (int a = 0; a < 8; ++a) {
      nodes[a] = element_nodes(element, a);
      for (int i = 0; i < 3; ++i) {
        X[a][i] = coordinates(nodes[a], i);
        u[a][i] = displacements(nodes[a], i);
      }
    }
    double element_energy, r[24], K[24][24];
    if (elements::solid_element<elements::Hex8Shape>(law, X, u, 2, element_energy, r, K) != elements::ElementStatus::ok)
      return;
    energy += element_energy;
    // The element's columns in ascending order (sumIntoValues with is_sorted searches forward), as ElementScatter.
    int order[24], columns[24];
    for (int p = 0; p < 24; ++p) {
      const int column = 3 * nodes[p / 3] + p % 3;
      int q = p;
      for (; q > 0 && columns[q - 1] > column; --q) {
        columns[q] = columns[q - 1];
        order[q] = order[q - 1];
      }
      columns[q] = column;
      order[q] = p;
    }
    double values[24];
    for (int p = 0; p < 24; ++p) {
      const int row = 3 * nodes[p / 3] + p % 3;
      if (atomic)
        Kokkos::atomic_add(&residual(row), r[p]);
      else
        residual(row) += r[p];
      for (int q = 0; q < 24; ++q) values[q] = K[p][order[q]];
      matrix.sumIntoValues(row, columns, 24, values, true, atomic);
    }
  }
};

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// The node graph's sparsity, three rows and columns per node.
LocalMatrix make_matrix(const mesh::HexMesh& mesh)
{
  std::vector<std::set<int>> neighbours(mesh.node_count());
  for (const auto& element : mesh.elements)
    for (auto a : element)
      for (auto b : element) neighbours[a].insert(int(b));
  const int rows = int(3 * mesh.node_count());
  Kokkos::View<LocalMatrix::size_type*, device_type> row_map("row map", rows + 1);
  auto row_map_host = Kokkos::create_mirror_view(row_map);
  row_map_host(0) = 0;
  for (int row = 0; row < rows; ++row) row_map_host(row + 1) = row_map_host(row) + 3 * neighbours[row / 3].size();
  Kokkos::View<int*, device_type> entries("entries", row_map_host(rows));
  auto entries_host = Kokkos::create_mirror_view(entries);
  for (int row = 0; row < rows; ++row) {
    auto k = row_map_host(row);
    for (int node : neighbours[row / 3])
      for (int i = 0; i < 3; ++i) entries_host(k++) = 3 * node + i;
  }
  Kokkos::deep_copy(row_map, row_map_host);
  Kokkos::deep_copy(entries, entries_host);
  Kokkos::View<double*, device_type> values("values", entries.extent(0));
  return LocalMatrix("tangent", rows, rows, int(entries.extent(0)), values, row_map, entries);
}

// Greedy colouring: each element takes the lowest colour none of its nodes' elements has taken.
std::vector<std::vector<int>> colour_elements(const mesh::HexMesh& mesh)
{
  std::vector<std::uint64_t> taken(mesh.node_count(), 0);
  std::vector<std::vector<int>> colours;
  for (int element = 0; element < int(mesh.element_count()); ++element) {
    std::uint64_t used = 0;
    for (auto node : mesh.elements[element]) used |= taken[node];
    int colour = 0;
    while (used & (std::uint64_t(1) << colour)) ++colour;
    if (colour >= 64) throw std::runtime_error("more than 64 colours");
    for (auto node : mesh.elements[element]) taken[node] |= std::uint64_t(1) << colour;
    if (colour >= int(colours.size())) colours.resize(colour + 1);
    colours[colour].push_back(element);
  }
  return colours;
}

Kokkos::View<const int*, device_type> device_list(const std::vector<int>& list)
{
  Kokkos::View<int*, device_type> view("element list", list.size());
  auto host = Kokkos::create_mirror_view(view);
  for (std::size_t k = 0; k < list.size(); ++k) host(k) = list[k];
  Kokkos::deep_copy(view, host);
  return view;
}

}  // namespace

int main(int argc, char** argv)
{
  Kokkos::ScopeGuard kokkos_scope(argc, argv);
  if (argc < 2) {
    std::cerr << "usage: scatter_benchmark <coarse|medium|fine> [repetitions]   (KOKKOS_NUM_THREADS=n)\n";
    return 2;
  }
  const std::string level = argv[1];
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  const geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  mesh::MeshParameters parameters;
  parameters.level = level;
  const auto mesh = mesh::mesh_spatula(shape, parameters);
  const int element_count = int(mesh.element_count());

  Kokkos::View<int* [8], device_type> element_nodes("element nodes", element_count);
  Kokkos::View<double* [3], device_type> coordinates("coordinates", mesh.node_count()),
      displacements("displacements", mesh.node_count());
  {
    auto nodes = Kokkos::create_mirror_view(element_nodes);
    auto X = Kokkos::create_mirror_view(coordinates);
    auto u = Kokkos::create_mirror_view(displacements);
    for (int e = 0; e < element_count; ++e)
      for (int a = 0; a < 8; ++a) nodes(e, a) = int(mesh.elements[e][a]);
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      for (int i = 0; i < 3; ++i) {
        X(n, i) = mesh.coordinates[n][i];
        // A smooth, moderate deformation (a few per cent strain), the same in every run.
        u(n, i) = 0.02 * mesh.coordinates[n][(i + 1) % 3] * std::sin(0.01 * mesh.coordinates[n][i] + i);
      }
    Kokkos::deep_copy(element_nodes, nodes);
    Kokkos::deep_copy(coordinates, X);
    Kokkos::deep_copy(displacements, u);
  }
  const auto matrix = make_matrix(mesh);
  Kokkos::View<double*, device_type> residual("residual", 3 * mesh.node_count());
  const auto law = laws::NeoHookean::from_young(2.0, 0.2);

  std::vector<int> all(element_count);
  for (int e = 0; e < element_count; ++e) all[e] = e;
  const auto colours = colour_elements(mesh);
  std::vector<Kokkos::View<const int*, device_type>> colour_lists;
  for (const auto& list : colours) colour_lists.push_back(device_list(list));

  ScatterKernel<true> atomic{matrix, residual, element_nodes, coordinates, displacements, device_list(all), law};
  auto assemble = [&](bool coloured) {
    Kokkos::deep_copy(matrix.values, 0.0);
    Kokkos::deep_copy(residual, 0.0);
    Kokkos::fence();
    const auto start = std::chrono::steady_clock::now();
    double energy = 0.0;
    if (!coloured) {
      Kokkos::parallel_reduce("spatula: scatter benchmark, atomic", Kokkos::RangePolicy<execution_space>(0, element_count),
                              atomic, energy);
    } else {
      for (const auto& list : colour_lists) {
        ScatterKernel<false> plain{matrix, residual, element_nodes, coordinates, displacements, list, law};
        double colour_energy = 0.0;
        Kokkos::parallel_reduce("spatula: scatter benchmark, one colour",
                                Kokkos::RangePolicy<execution_space>(0, int(list.extent(0))), plain, colour_energy);
        energy += colour_energy;
      }
    }
    Kokkos::fence();
    return std::make_pair(seconds_since(start), energy);
  };

  std::vector<double> atomic_times, coloured_times;
  auto values_atomic = Kokkos::create_mirror_view(matrix.values);
  auto values_coloured = Kokkos::create_mirror_view(matrix.values);
  double energy_atomic = 0.0, energy_coloured = 0.0;
  for (int repetition = 0; repetition < repetitions; ++repetition) {
    const auto [atomic_seconds, atomic_energy] = assemble(false);
    atomic_times.push_back(atomic_seconds);
    energy_atomic = atomic_energy;
    Kokkos::deep_copy(values_atomic, matrix.values);
    const auto [coloured_seconds, coloured_energy] = assemble(true);
    coloured_times.push_back(coloured_seconds);
    energy_coloured = coloured_energy;
    Kokkos::deep_copy(values_coloured, matrix.values);
  }
  double largest = 0.0, difference = 0.0;
  for (std::size_t k = 0; k < values_atomic.extent(0); ++k) {
    largest = std::max(largest, std::abs(values_atomic(k)));
    difference = std::max(difference, std::abs(values_atomic(k) - values_coloured(k)));
  }
  const double atomic_median = median(atomic_times), coloured_median = median(coloured_times);
  std::cout << "level,backend,threads,elements,colours,atomic_s,coloured_s,atomic_elements_per_s,"
               "coloured_elements_per_s,relative_matrix_difference,relative_energy_difference\n"
            << level << ',' << execution_space::name() << ',' << execution_space::concurrency() << ','
            << element_count << ',' << colours.size() << ',' << atomic_median << ',' << coloured_median << ','
            << element_count / atomic_median << ',' << element_count / coloured_median << ',' << difference / largest
            << ',' << std::abs(energy_atomic - energy_coloured) / std::abs(energy_atomic) << '\n';
  return 0;
}
