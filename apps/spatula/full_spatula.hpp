#pragma once
// The mesh is one half of the spatula (symmetric about the XZ plane, paper Sec. 4): its reactions, energies, work
// and contact area are half the spatula's, its positions and angles the spatula's. Every value the program reports
// is the full spatula's: this is the one place the factor is applied.
#include "analysis/load_history.hpp"

namespace spatula::app {

constexpr double halves = 2.0;   // full spatula / half model, for forces, moments, energies, work and areas

inline double full_spatula(double half_model_value) { return halves * half_model_value; }

// A converged state's reactions, energies and work as the full spatula's.
struct FullSpatula {
  double moment, force, slide_force;            // M_y [nN nm], P_z, P_x [nN]
  double internal_energy, contact_energy;       // Pi_int, Pi_c [nN nm]
  // Pi_ext, and the energy dissipated: released by the jumps and (a friction law) by sliding [nN nm]
  double external_work, dissipated;
};

inline FullSpatula full_spatula(const analysis::LoadPoint& p)
{
  return {halves * p.moment,          halves * p.force,          halves * p.slide_force, halves * p.internal_energy,
          halves * p.contact_energy,  halves * p.external_work,  halves * (p.dissipated + p.sliding)};
}

}  // namespace spatula::app
