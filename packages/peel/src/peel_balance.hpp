#pragma once
// The steady peel force of a strip from the energy balance of peeling (Kendall 1975), with the adhered part held at
// a pre-stretch lambda_0 by its bond (the pre-tension of Chen, Wu and Gao 2009, J. R. Soc. Interface 6:529), for the
// strip's own finite-strain law in uniaxial tension.
//
// Peeling a reference length dS moves the front back by lambda_0 dS along the substrate and adds lambda dS to the
// arm, so the pull F along the peel direction (at theta to the substrate) does F (lambda - lambda_0 cos theta) dS of
// work; the peeled material's stored energy per reference length goes from W(lambda_0) to W(lambda), and the bond
// gives up w b dS, w per undeformed area as the contact integral counts it (a stretched face holds the same
// molecules, not more):
//
//   F (lambda - lambda_0 cos theta) - [W(lambda) - W(lambda_0)] = w b,     F = W'(lambda).
//
// With lambda_0 = 1 and a linear strip (W = E b h eps^2 / 2) this is Kendall's (F/b)^2 / (2 E h) +
// (F/b)(1 - cos theta) = w; with small strains and a pre-strain eps_0 it gives
//   F / (E b h) = eps_0 cos theta - (1 - cos theta) + sqrt((1 - cos theta - eps_0 cos theta)^2 + 2 w / (E h) - eps_0^2):
// pre-tension raises the force at small angles, lowers it at large ones, and above eps_0^2 = 2 w / (E h) the strip
// peels off by itself wherever lambda_0 cos theta < 1.
#include "laws/neo_hookean.hpp"

namespace spatula::peel {

// A bar of the law in uniaxial tension at stretch `stretch` (lateral stresses zero): its lateral stretch, the
// energy per unit reference volume and the nominal stress P_11.
struct UniaxialState {
  double stretch = 1.0, lateral_stretch = 1.0, energy = 0.0, stress = 0.0;
};
UniaxialState uniaxial_tension(const laws::NeoHookean& law, double stretch);
// The stretch at which the bar carries the nominal stress `stress` (>= 0).
double uniaxial_stretch(const laws::NeoHookean& law, double stress);

struct StripSection {
  double width = 0.0, thickness = 0.0;   // reference [nm]
};

// The steady peel force per reference width F/b [nN/nm] that satisfies the balance above, for the work of adhesion
// w [nN/nm], the peel angle theta [rad] and the adhered part's pre-stretch lambda_0 (1: Kendall): the larger root,
// where the surplus grows with the pull (lambda > lambda_0 cos theta). 0 where no pull holds the front (the surplus
// is positive at every pull: the strip peels off by itself).
double steady_peel_force(const laws::NeoHookean& law, const StripSection& section, double work_of_adhesion,
                         double angle, double pre_stretch);

}  // namespace spatula::peel
