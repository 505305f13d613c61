#pragma once
// A load path as data: an ordered list of stages, each moving one motion of the end face (rotate it, lift it, slide
// it along X) or the force on it (pull it along Z, push it along X) to a target, with its own step control and the
// end-face motions it leaves free. A scene writes them
// in 'Loading/Stages' ('Loading/type' = stages), or keeps the fixed types: 'rotation' is the one-stage path
// [rotation], 'lift' the two-stage path [rotation, lift], with the same results.
#include "analysis/step_control.hpp"
#include "discretization/discrete_system.hpp"

#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

namespace spatula::app {

// What a stage moves: in the order of stage_kinds() ("rotate", "lift", "slide x", "lift force", "slide x force").
enum class StageKind { rotate, lift, slide, lift_force, slide_force };
const std::vector<std::string>& stage_kinds();

struct Stage {
  std::string name;            // curve.csv's stage column, messages: the stage's sublist name
  StageKind kind = StageKind::rotate;
  // rotate: theta_y [deg]; lift, slide: the face centre's motion along the lift and slide directions [nm]; lift
  // force, slide force: the net force on the end face along them [nN, full spatula] (u_z, u_x, P_z, P_x at the
  // default 'Loading/pull angle' of 90 deg)
  double target = 0.0;
  bool relative = false;       // the target counted from where the stage starts
  analysis::StepParameters steps;
  bool free_lift = false;      // rotate, slide (x force): zero net Z force on the face (else u_z held)
  bool free_slide = false;     // lift (force): zero net X force on the face (else u_x held)
  bool checkpoints = false;    // rotate: stop at 'Loading/checkpoints at theta_y' on the way and write them
  // lift, slide: end the stage at the first state whose net force along its motion (P_z, P_x; full spatula) has
  // reached this value from where the stage began [nN]; 0: none (the stage ends at its target)
  double stop_at_force = 0.0;

  discretization::Master master() const;   // the motion it moves, or the one its force drives
  bool force() const { return kind == StageKind::lift_force || kind == StageKind::slide_force; }
  // Which end-face motions are prescribed while it goes (the moved one, and those it holds).
  discretization::MasterControl control() const;
};

// Declares the sublist 'Loading/Stages' (free-form: read_stages validates each stage against its kind's keys).
void declare_stages(Teuchos::ParameterList& loading);
// The stages of 'Loading/Stages', in the order written. Throws parameters::InputError naming the stage for a missing
// kind or target, an unknown kind, a key its kind does not take (a motion it cannot leave free), a name that cannot
// be a column of curve.csv, or no stage at all.
std::vector<Stage> read_stages(const Teuchos::ParameterList& stages);

}  // namespace spatula::app
