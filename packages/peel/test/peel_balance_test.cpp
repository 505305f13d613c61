// The energy balance of peeling (peel/peel_balance.hpp) against exact relations and its closed-form limits: the
// bar's uniaxial state, Kendall's linear balance, and the small-strain pre-tension result of Chen, Wu and Gao.
#include "peel/peel_balance.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatula;

namespace {

const auto law = laws::NeoHookean::from_young(2.0, 0.2);
const peel::StripSection section{2.5, 5.0};
constexpr double young = 2.0, thickness = 5.0;

// Kendall's linear strip: (F/b)^2 / (2 E h) + (F/b)(1 - cos theta) = w.
double kendall(double w, double angle)
{
  const double a = 1.0 / (2.0 * young * thickness), c = 1.0 - std::cos(angle);
  return (-c + std::sqrt(c * c + 4.0 * a * w)) / (2.0 * a);
}

// The small-strain balance with pre-strain eps0: F / (E b h) = -a + sqrt(a^2 - eps0^2 + 2 w / (E h)),
// a = 1 - cos theta - eps0 cos theta (0 where the root is not real: no pull holds the front).
double small_strain(double w, double angle, double eps0)
{
  const double a = 1.0 - std::cos(angle) - eps0 * std::cos(angle);
  const double discriminant = a * a - eps0 * eps0 + 2.0 * w / (young * thickness);
  return discriminant < 0.0 ? 0.0 : std::max(0.0, young * thickness * (-a + std::sqrt(discriminant)));
}

}  // namespace

TEST(UniaxialTension, LateralStressVanishesAndTheEnergyIsTheStressPotential)
{
  for (double stretch : {0.9, 1.001, 1.05, 1.3}) {
    const auto state = peel::uniaxial_tension(law, stretch);
    // P_22 = 0 of the Neo-Hookean law: mu m^2 + Lambda ln(l m^2) - mu = 0.
    EXPECT_NEAR(law.mu * state.lateral_stretch * state.lateral_stretch +
                    law.lambda * std::log(stretch * state.lateral_stretch * state.lateral_stretch) - law.mu,
                0.0, 1e-12);
    // With the lateral stresses zero the energy's total derivative along the stretch is P_11.
    const double h = 1e-6;
    const double slope =
        (peel::uniaxial_tension(law, stretch + h).energy - peel::uniaxial_tension(law, stretch - h).energy) / (2 * h);
    EXPECT_NEAR(slope, state.stress, 1e-7 * std::max(1.0, std::abs(state.stress)));
    EXPECT_NEAR(peel::uniaxial_stretch(law, std::max(0.0, state.stress)), std::max(1.0, stretch), 1e-12);
  }
  // Small strain: Young's modulus and Poisson's ratio.
  const auto small = peel::uniaxial_tension(law, 1.0 + 1e-6);
  EXPECT_NEAR(small.stress / 1e-6, young, 1e-5);
  EXPECT_NEAR((1.0 - small.lateral_stretch) / 1e-6, 0.2, 1e-5);
}

TEST(PeelBalance, WithoutPreTensionItIsKendallsBalance)
{
  for (double angle_degrees : {10.0, 45.0, 90.0, 135.0}) {
    const double angle = angle_degrees * M_PI / 180.0, w = 0.01;
    const double force = peel::steady_peel_force(law, section, w, angle, 1.0);
    const double arm_strain = force / (young * thickness);
    // The finite-strain law departs from the linear strip by the order of the arm's strain.
    EXPECT_NEAR(force / kendall(w, angle), 1.0, 2.0 * arm_strain) << angle_degrees << " deg";
  }
}

TEST(PeelBalance, SmallPreStrainsFollowChenWuGao)
{
  for (double angle_degrees : {5.0, 30.0, 90.0}) {
    const double angle = angle_degrees * M_PI / 180.0, w = 1e-3, eps0 = 2e-3;
    const double force = peel::steady_peel_force(law, section, w, angle, 1.0 + eps0);
    EXPECT_NEAR(force / small_strain(w, angle, eps0), 1.0, 1e-2) << angle_degrees << " deg";
  }
}

TEST(PeelBalance, PreTensionRaisesTheForceAtSmallAnglesAndLowersItAtLargeOnes)
{
  const double w = 0.01, eps0 = 0.02;   // eps0^2 < 2 w / (E h): the strip stays bonded without a pull
  const double small = 5.0 * M_PI / 180.0, large = M_PI / 2.0;
  EXPECT_GT(peel::steady_peel_force(law, section, w, small, 1.0 + eps0),
            1.3 * peel::steady_peel_force(law, section, w, small, 1.0));
  EXPECT_LT(peel::steady_peel_force(law, section, w, large, 1.0 + eps0),
            0.85 * peel::steady_peel_force(law, section, w, large, 1.0));
}

TEST(PeelBalance, AboveTheCriticalPreStrainOnlySmallAnglesHold)
{
  const double w = 1e-3, eps0 = 0.03;   // eps0^2 > 2 w / (E h) = 2e-4
  EXPECT_EQ(peel::steady_peel_force(law, section, w, M_PI / 2.0, 1.0 + eps0), 0.0);
  EXPECT_EQ(peel::steady_peel_force(law, section, w, 10.0 * M_PI / 180.0, 1.0 + eps0), 0.0);
  const double angle = 2.0 * M_PI / 180.0;
  const double force = peel::steady_peel_force(law, section, w, angle, 1.0 + eps0);
  EXPECT_GT(force, 0.0);
  EXPECT_NEAR(force / small_strain(w, angle, eps0), 1.0, 0.05);   // strains of 3-4 %: finite-strain terms
}
