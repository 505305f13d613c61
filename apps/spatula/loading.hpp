#pragma once
// What a scene does with the spatula: mesh only, or follow a load path of stages (stages.hpp). "Loading/type" is
// checked against loading_types() ("none", "rotation", "lift", "stages"): 'rotation' rotates the end face to theta_y
// (one stage), 'lift' rotates there and then raises the face to 'final lift' (two stages), 'stages' runs
// 'Loading/Stages'. main.cpp runs no load path for "none".
#include "stages.hpp"

#include "analysis/load_stepping.hpp"

#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <string>
#include <vector>

namespace spatula::app {

enum class LoadingType { none, rotation, lift, stages };   // in the order of loading_types()

struct LoadingParameters {
  LoadingType type = LoadingType::none;
  double theta_y = 30.0;          // rotation: final inclination; lift: the inclination held [deg]
  double final_lift = 100.0;      // lift: u_z of the face centre at the end, from the undeformed state [nm]
  bool lift_relative = false;     // final lift counted from where the lift starts (a pre-rotated state)
  bool free_lift = true;          // while rotating: zero net Z force on the face (else u_z held at 0)
  bool free_slide = false;        // while lifting: zero net X force on the face (else u_x held)
  bool hold_contact_surface = false;   // the pad's bottom held at Z = 0 (a check without adhesion)
  double pull_angle = 90.0;       // beta: the lift direction's angle to the substrate [deg] (pull_directions.hpp)
  // Smallest and largest increments: those of every validated run; in the error benchmark's step set (coarse
  // pull-off at 60 deg) 2 deg / 5 nm took less CPU than half or twice that, with the same P_max to 3e-5.
  analysis::StepParameters rotation_steps{1.0, 0.01, 2.0};   // [deg]
  analysis::StepParameters lift_steps{2.0, 0.01, 5.0};       // [nm]
  std::string past_instabilities = "jump";   // an analysis::InstabilityPolicies name
  std::string restart_file;               // start from a checkpoint of an earlier run (empty: undeformed)
  double restart_theta_y = 60.0;          // which one [deg]
  bool restart_from_last_state = false;   // the last converged state of a stopped run instead
  std::vector<double> checkpoints;        // inclinations [deg] at which a rotation leaves checkpoints
  analysis::JumpParameters jump;
  double step_balance_tolerance = 1e-4;   // over Pi_c0 (JumpParameters holds it in nN nm)
  analysis::ArcLengthParameters arc_length_steps;
  std::vector<Stage> stages;              // the load path: 'Loading/Stages', or the fixed type's stages

  static void declare(Teuchos::ParameterList& loading);
  static LoadingParameters from(const Teuchos::ParameterList& loading);
};

const std::vector<std::string>& loading_types();
// The policy of 'Loading/past instabilities' (with the arc-length steps where it uses them).
std::shared_ptr<const analysis::InstabilityPolicy> instability_policy(const LoadingParameters& loading);

}  // namespace spatula::app
