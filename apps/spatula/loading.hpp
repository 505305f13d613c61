#pragma once
// What a scene does with the spatula: mesh only, peel by rotating the end face, or pull off by lifting it at a
// fixed inclination (after rotating there). A registry maps each "Loading/type" name to its run.
#include "load_stepping.hpp"

#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

namespace spatula::app {

struct LoadingParameters {
  std::string type = "none";
  double theta_y = 30.0;          // rotation: final inclination; lift: the inclination held [deg]
  double final_lift = 100.0;      // lift: u_z of the face centre at the end, from the undeformed state [nm]
  bool lift_relative = false;     // final lift counted from where the lift starts (a pre-rotated state)
  bool free_lift = true;          // while rotating: zero net Z force on the face (else u_z held at 0)
  bool free_slide = false;        // while lifting: zero net X force on the face (else u_x held)
  bool hold_contact_surface = false;   // the pad's bottom held at Z = 0 (a check without adhesion)
  analysis::StepParameters rotation_steps, lift_steps;
  std::string past_instabilities = "jump";   // a name in instability_methods()
  std::string restart_file;               // start from a checkpoint of an earlier run (empty: undeformed)
  double restart_theta_y = 0.0;           // which one [deg]
  bool restart_from_last_state = false;   // the last converged state of a stopped run instead
  std::vector<double> checkpoints;        // inclinations [deg] at which a rotation leaves checkpoints
  analysis::JumpParameters jump;
  double step_balance_tolerance = 1e-4;   // over Pi_c0 (JumpParameters holds it in nN nm)
  analysis::ArcLengthParameters arc_length_steps;

  static void declare(Teuchos::ParameterList& loading);
  static LoadingParameters from(const Teuchos::ParameterList& loading);
};

const std::vector<std::string>& loading_types();
const std::vector<std::string>& instability_methods();   // "stop", "jump", "arc-length"

}  // namespace spatula::app
