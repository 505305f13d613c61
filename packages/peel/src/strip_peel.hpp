#pragma once
// Kendall's thin-film peel as a reusable experiment (a test and a benchmark run it): a strip adhering to a flat
// substrate, its end pulled along a fixed direction at the peel angle theta, the end free to rotate and to move
// across the pull (a dead-load direction). In steady peeling
//   (F/b)^2 / (2 E h) + (F/b)(1 - cos theta) = w_adh
// holds whatever the bending stiffness, once the peeled arm is long against the bending length sqrt(D b / F).
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
  double energy_balance = 0.0;           // Kendall's F/b [nN/nm]
  std::vector<std::pair<double, double>> curve;   // (pull [nm], F/b [nN/nm]) at every converged step
};

StripPeelResult peel_strip(const StripPeelParameters& parameters, Teuchos::RCP<const Teuchos::Comm<int>> comm);

}  // namespace spatula::peel
