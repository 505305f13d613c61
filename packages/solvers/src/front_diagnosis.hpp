#pragma once
// Where a Newton iteration's step is limited: the contact points its full step would carry across the
// Lennard-Jones law's inflection (or move by more than a fraction of r0), where they sit, and the energy along the
// full step. At the peel front the energy line search cuts the step where the energy, having fallen, rises again
// over a barrier: these points are the suspects. Written into the convergence table under each iteration.
#include "solvers/spatula_model.hpp"

#include <array>
#include <string>

namespace spatula::solvers {

struct FrontDiagnosis {
  discretization::GapChanges gaps;
  // Pi(x + t dx) - Pi(x) at t = 0.25, 0.5, 0.75 and 1 of the full step dx [nN nm, half model]
  static constexpr std::array<double, 4> fractions = {0.25, 0.5, 0.75, 1.0};
  std::array<double, 4> energy_change{};
};

// The diagnosis of the full step from `from` to `full` (collective; the system's evaluations only: the model's
// counters and last evaluation are left as they were). `fraction`: a gap change above fraction x r0 counts as large.
FrontDiagnosis diagnose_front(const SpatulaModel& model, const discretization::Vector& from,
                              const discretization::Vector& full, double fraction = 0.25);

// One line of the convergence table: "full step: N contact points cross ...", ending with a newline.
std::string front_line(const FrontDiagnosis& diagnosis, double fraction = 0.25);

}  // namespace spatula::solvers
