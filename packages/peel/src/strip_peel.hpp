#pragma once
// Kendall's thin-film peel as a reusable experiment (a test and a benchmark run it): a strip adhering to a flat
// substrate, its end pulled along a fixed direction at the peel angle theta, the end free to rotate and to move
// across the pull (a dead-load direction). In steady peeling
//   (F/b)^2 / (2 E h) + (F/b)(1 - cos theta) = w_adh
// holds whatever the bending stiffness, once the peeled arm is long against the bending length sqrt(D b / F).
//
// With a pre-strain (Chen, Wu and Gao 2009) the strip is first stretched along the substrate on a frictionless bond
// (its far end held), then bonded where it lies by the law, which must hold it along the substrate (stiction or
// adhesive friction: the state carried over, the law's anchors set there), and peeled: peel_balance.hpp gives the
// steady force for the adhered part's stretch, measured from the stretching force.
#include "contact/adhesion.hpp"

#include <Teuchos_Comm.hpp>

#include <string>
#include <utility>
#include <vector>

namespace spatula::peel {

struct StripPeelParameters {
  double angle_degrees = 90.0;
  double length = 160.0, half_width = 2.5, thickness = 5.0;   // [nm]; the model is the half Y >= 0
  double young = 2.0;                                          // [GPa]
  int elements_along = 64, layers = 4;
  std::string law = "stiction";   // no slip, as Kendall assumes (frictionless: the far end is held in X)
  contact::AdhesiveFriction friction;   // law = "adhesive friction": its sliding limit and stick
  double pre_strain = 0.0;        // the adhered part's stretch before the peel, less 1 (0: none, Kendall)
  discretization::Enrichment enrichment = discretization::Enrichment::q1c2;
  int quadrature = 4;
  double pull = 110.0;            // end displacement along the pull direction [nm]
  double window_start = 70.0;     // steady force averaged over pulls from here to the end [nm]
  double maximum_step = 1.0;      // [nm]
};

struct StripPeelResult {
  bool completed = false;
  std::string failure;
  double steady_force_per_width = 0.0;   // averaged over the window [nN/nm]
  double energy_balance = 0.0;           // the steady F/b of the energy balance (peel_balance.hpp) [nN/nm]
  double pre_stretch = 1.0;              // the adhered part's stretch when the peel began (from its tension)
  double sliding_dissipation = 0.0;      // dissipated by the law's sliding during the peel (half model) [nN nm]
  std::vector<std::pair<double, double>> curve;   // (pull [nm], F/b [nN/nm]) at every converged step
};

StripPeelResult peel_strip(const StripPeelParameters& parameters, Teuchos::RCP<const Teuchos::Comm<int>> comm);

}  // namespace spatula::peel
