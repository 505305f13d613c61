// The peel front's diagnosis of a Newton step (solvers/front_diagnosis.hpp) on the adhering bar of adhering_bar.hpp
// (1 x 1 x 8 elements, one contact face with 2 x 2 quadrature points at X, Y = 2 -+ 2/sqrt(3) nm): a rigid
// translation of the bar away from the substrate by d carries every point from the equilibrium gap g_eq across the
// law's inflection r0 5^(-1/6) once g_eq + d is beyond it, and changes the energy by exactly A (phi(g_eq + t d) -
// phi(g_eq)) at t of the step (no strain, one gap everywhere), all of it the limiting points' share; a short
// translation carries none across. In a Newton solve with its convergence table and 'front diagnosis', every
// iteration's row is followed by the diagnosis of its full step; without 'front diagnosis' the table has no such line.
// The points still adhering after a rigid slide along the substrate report its length as their mean slip.
#include "adhering_bar.hpp"
#include "discretization/system_fields.hpp"
#include "solvers/front_diagnosis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

using namespace spatula;

using test::translated;

TEST(FrontDiagnosis, ARigidLiftAcrossTheInflectionCountsEveryPointAndTheLawsEnergy)
{
  test::AdheringBar bar;
  bar.system->set_control({{true, true, true}});
  const auto& law = bar.bar.law;
  const double d = 0.3;   // g_eq = 0.255 nm -> 0.555 nm, past the inflection at 0.305 nm
  ASSERT_GT(law.equilibrium_gap() + d, law.strongest_attraction_gap());
  const auto from = translated(bar, 0.0), to = translated(bar, d);
  const auto diagnosis = solvers::diagnose_front(*bar.model, *from, *to, 0.25);
  EXPECT_EQ(diagnosis.gaps.crossing, 4);
  EXPECT_EQ(diagnosis.gaps.large, 4);   // 0.3 nm > 0.25 r0 = 0.1 nm
  const double half = 0.5 * test::AdheringBar::side, spread = half / std::sqrt(3.0);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(diagnosis.gaps.mean[i], half, 1e-12);
    EXPECT_NEAR(diagnosis.gaps.spread[i], spread, 1e-9);
  }
  const double area = test::AdheringBar::side * test::AdheringBar::side;
  for (std::size_t k = 0; k < solvers::FrontDiagnosis::fractions.size(); ++k) {
    const double t = solvers::FrontDiagnosis::fractions[k];
    const double expected = area * (bar.bar.energy(law.equilibrium_gap() + t * d) - bar.bar.energy(law.equilibrium_gap()));
    EXPECT_NEAR(diagnosis.energy_change[k], expected, 1e-10 * std::abs(expected)) << "at t = " << t;
    EXPECT_NEAR(diagnosis.gaps.energy_change[k], expected, 1e-10 * std::abs(expected)) << "every point limits";
  }
  // A short lift stays on the near side of the inflection and below 0.25 r0: nothing to name.
  const auto short_lift = solvers::diagnose_front(*bar.model, *from, *translated(bar, 0.02), 0.25);
  EXPECT_EQ(short_lift.gaps.crossing, 0);
  EXPECT_EQ(short_lift.gaps.large, 0);
  // ... unless the fraction of r0 is smaller than its change (0.02 nm = 0.05 r0).
  EXPECT_EQ(solvers::diagnose_front(*bar.model, *from, *translated(bar, 0.02), 0.04).gaps.large, 4);
}

// The bar moved rigidly by s along X and d along Z.
Teuchos::RCP<discretization::Vector> moved(const test::AdheringBar& bar, double s, double d)
{
  auto x = translated(bar, d);
  std::vector<double> u(3 * bar.mesh.node_count(), 0.0);
  for (std::int64_t n = 0; n < bar.mesh.node_count(); ++n) {
    u[3 * n] = s;
    u[3 * n + 2] = d;
  }
  discretization::set_displacements(*bar.system, *x, u);
  return x;
}

TEST(FrontDiagnosis, TheAdheringPointsSlipIsTheirTravelAlongTheSubstrate)
{
  test::AdheringBar bar;
  bar.system->set_control({{true, true, true}});
  const double area = test::AdheringBar::side * test::AdheringBar::side;
  // Slid by 3.5 nm at the equilibrium gap: every point still adheres and has travelled 3.5 nm.
  const auto from = translated(bar, 0.0);
  const auto slid = bar.system->contact_gap_changes(*from, *moved(bar, 3.5, 0.0), 0.25);
  EXPECT_NEAR(slid.adhering_area, area, 1e-12 * area);
  EXPECT_NEAR(slid.mean_slip, 3.5, 1e-12);
  EXPECT_EQ(slid.crossing, 0);
  // Slid and lifted past the inflection: nothing adheres, so nothing has slid.
  const auto lifted = bar.system->contact_gap_changes(*from, *moved(bar, 3.5, 0.3), 0.25);
  EXPECT_EQ(lifted.adhering_area, 0.0);
  EXPECT_EQ(lifted.mean_slip, 0.0);
  EXPECT_EQ(lifted.crossing, 4);
}

TEST(FrontDiagnosis, EveryRowOfTheConvergenceTableIsFollowedByItsFullStepsDiagnosis)
{
  solvers::NewtonParameters parameters;
  parameters.front_diagnosis = true;
  test::AdheringBar bar(parameters);
  bar.system->set_control(discretization::MasterControl::moving(discretization::Master::lift));
  auto x = bar.system->create_vector();
  bar.system->set_master(*x, discretization::Master::lift, 1.0);
  std::ostringstream table;
  const auto result = bar.newton->solve(*x, &table);
  ASSERT_TRUE(result.converged);
  ASSERT_GE(result.iterations.size(), 2u);
  std::istringstream lines(table.str());
  std::string line;
  int rows = 0, diagnoses = 0;
  bool expect_diagnosis = false;
  while (std::getline(lines, line)) {
    if (expect_diagnosis) {
      EXPECT_NE(line.find("full step: "), std::string::npos) << line;
      EXPECT_NE(line.find("Pi - Pi_0 at t = 0.25: "), std::string::npos) << line;
      ++diagnoses;
      expect_diagnosis = false;
    } else if (line.find("full step") == std::string::npos && line.find("newton") == std::string::npos) {
      std::istringstream row(line);
      int iteration = -1;
      if (row >> iteration && iteration > 0) {
        ++rows;
        expect_diagnosis = true;
      }
    }
  }
  EXPECT_EQ(rows, static_cast<int>(result.iterations.size()));
  EXPECT_EQ(diagnoses, rows);

  test::AdheringBar plain;   // the default: tables without the diagnosis
  plain.system->set_control(discretization::MasterControl::moving(discretization::Master::lift));
  auto y = plain.system->create_vector();
  plain.system->set_master(*y, discretization::Master::lift, 1.0);
  std::ostringstream plain_table;
  ASSERT_TRUE(plain.newton->solve(*y, &plain_table).converged);
  EXPECT_EQ(plain_table.str().find("full step"), std::string::npos);
}
