// Kendall's thin-film peel (peel/strip_peel.hpp): a 5 nm thick strip (E = 2 GPa), stiction law (no slip, as
// Kendall assumes), Q1C2. The pull per width averaged over a window of steady peeling must match the energy
// balance within 2 % at 90 and 45 deg. (A 10 nm strip has a bending length of 75 nm at 90 deg and would need a
// strip four times longer than CI affords to reach the steady state.)
#include "peel/strip_peel.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <gtest/gtest.h>

#include <iostream>

using namespace spatula;

namespace {

void expect_energy_balance(double angle, double pull, double window_start)
{
  peel::StripPeelParameters parameters;
  parameters.angle_degrees = angle;
  parameters.pull = pull;
  parameters.window_start = window_start;
  auto comm = Teuchos::DefaultComm<int>::getComm();
  const auto result = peel::peel_strip(parameters, comm);
  ASSERT_TRUE(result.completed) << result.failure;
  if (comm->getRank() == 0)
    std::cout << "peel at " << angle << " deg: steady F/b = " << result.steady_force_per_width
              << " nN/nm, energy balance " << result.energy_balance << " nN/nm ("
              << 100.0 * (result.steady_force_per_width / result.energy_balance - 1.0) << " %)\n";
  EXPECT_NEAR(result.steady_force_per_width / result.energy_balance, 1.0, 0.02);
}

}  // namespace

TEST(Kendall, Peel90Degrees) { expect_energy_balance(90.0, 110.0, 70.0); }

TEST(Kendall, Peel45Degrees) { expect_energy_balance(45.0, 38.0, 24.0); }
