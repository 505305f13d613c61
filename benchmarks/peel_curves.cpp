// Peel force curves of Kendall's strip (peel/strip_peel.hpp) with Q1C1 and Q1C2 on the same mesh, for the docs.
//
//   peel_curves <angle deg> <pull nm> <window start nm> <elements along> <output.csv>
//
// Writes pull, F/b for both enrichments and prints the steady F/b against the energy balance.
#include "peel/strip_peel.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_GlobalMPISession.hpp>
#include <Tpetra_Core.hpp>

#include <chrono>
#include <fstream>
#include <iostream>

using namespace spatula;

int main(int argc, char** argv)
{
  Teuchos::GlobalMPISession session(&argc, &argv, nullptr);
  Tpetra::ScopeGuard kokkos_scope(&argc, &argv);   // Kokkos starts here, not lazily at the first Tpetra::Map
  auto comm = Teuchos::DefaultComm<int>::getComm();
  if (argc < 6) {
    std::cerr << "usage: peel_curves <angle> <pull> <window start> <elements along> <output.csv>\n";
    return 2;
  }
  peel::StripPeelParameters parameters;
  parameters.angle_degrees = std::atof(argv[1]);
  parameters.pull = std::atof(argv[2]);
  parameters.window_start = std::atof(argv[3]);
  parameters.elements_along = std::atoi(argv[4]);
  std::ofstream out(argv[5]);
  out << "enrichment,pull_nm,force_per_width_nN_per_nm\n";
  for (auto enrichment : {discretization::Enrichment::q1c1, discretization::Enrichment::q1c2}) {
    parameters.enrichment = enrichment;
    const char* name = enrichment == discretization::Enrichment::q1c1 ? "Q1C1" : "Q1C2";
    const auto start = std::chrono::steady_clock::now();
    const auto result = peel::peel_strip(parameters, comm);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const auto& [pull, force] : result.curve) out << name << "," << pull << "," << force << "\n";
    if (comm->getRank() == 0)
      std::cout << name << " at " << parameters.angle_degrees << " deg, " << parameters.elements_along
                << " elements along: steady F/b = " << result.steady_force_per_width << " nN/nm (energy balance "
                << result.energy_balance << ", " << 100.0 * (result.steady_force_per_width / result.energy_balance - 1.0)
                << " %), " << result.curve.size() << " steps, " << seconds << " s"
                << (result.completed ? "" : ", stopped: " + result.failure) << "\n";
  }
  return 0;
}
