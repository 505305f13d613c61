#include "stages.hpp"

#include "parameters/parameter_validation.hpp"

#include <algorithm>

namespace spatula::app {

namespace {

using discretization::Master;

// Each kind's unit, default increments, and the motions it may leave free.
struct KindRules {
  const char* unit;      // of its target
  analysis::StepParameters steps;
  bool takes_free_lift, takes_free_slide, takes_checkpoints;
  bool free_lift;        // default
  bool takes_stop_at_force = false;
};

const KindRules& rules(StageKind kind)
{
  static const KindRules rotate{"deg", {1.0, 0.01, 2.0}, true, false, true, true};
  static const KindRules lift{"nm", {2.0, 0.01, 5.0}, false, true, false, false, true};
  static const KindRules slide{"nm", {2.0, 0.01, 5.0}, true, false, false, false, true};
  static const KindRules lift_force{"nN", {1.0, 0.001, 5.0}, false, true, false, false};
  static const KindRules slide_force{"nN", {1.0, 0.001, 5.0}, true, false, false, false};
  switch (kind) {
  case StageKind::rotate: return rotate;
  case StageKind::lift: return lift;
  case StageKind::slide: return slide;
  case StageKind::lift_force: return lift_force;
  case StageKind::slide_force: return slide_force;
  }
  return rotate;
}

Teuchos::ParameterList valid_stage(StageKind kind)
{
  const auto& r = rules(kind);
  Teuchos::ParameterList valid;
  parameters::declare_string(valid, "kind", stage_kinds()[static_cast<int>(kind)],
                             "what the stage moves: rotate the end face (theta_y), lift it (u_z), slide it along X "
                             "(u_x), or the net force on it along Z (lift force, P_z) or X (slide x force, P_x): a "
                             "dead load, the face free to move along it", stage_kinds());
  parameters::declare_double(valid, "target", 0.0, std::string("where the stage ends [") + r.unit + "]",
                             parameters::Range::closed(kind == StageKind::rotate ? -180.0 : -1e4,
                                                       kind == StageKind::rotate ? 180.0 : 1e4));
  parameters::declare_bool(valid, "relative", false, "count 'target' from where the stage starts");
  analysis::StepParameters::declare(parameters::declare_sublist(valid, "Steps", std::string("increments [") + r.unit + "]"),
                                    r.steps);
  if (r.takes_free_lift)
    parameters::declare_bool(valid, "free lift", r.free_lift, "zero net Z force on the end face (false: u_z held)");
  if (r.takes_free_slide)
    parameters::declare_bool(valid, "free slide", false,
                             "zero net X force on the end face (false: u_x held); needs the stiction law");
  if (r.takes_checkpoints)
    parameters::declare_bool(valid, "checkpoints", true,
                             "stop at each of 'Loading/checkpoints at theta_y' on the way and write it");
  if (r.takes_stop_at_force)
    parameters::declare_double(valid, "stop at force", 0.0,
                               "end the stage at the first state whose net force along its motion (P_z for lift, P_x "
                               "for slide x; full spatula) has reached this value from where the stage began, before "
                               "the target [nN]; 0: none", parameters::Range::closed(-1e4, 1e4));
  return valid;
}

}  // namespace

const std::vector<std::string>& stage_kinds()
{
  static const std::vector<std::string> kinds = {"rotate", "lift", "slide x", "lift force", "slide x force"};
  return kinds;
}

Master Stage::master() const
{
  if (kind == StageKind::rotate) return Master::rotation;
  return kind == StageKind::lift || kind == StageKind::lift_force ? Master::lift : Master::slide;
}

discretization::MasterControl Stage::control() const
{
  discretization::MasterControl control;   // everything prescribed: the moved motion, and the others held
  if (master() != Master::lift) control.prescribed[static_cast<int>(Master::lift)] = !free_lift;
  if (master() == Master::lift) control.prescribed[static_cast<int>(Master::slide)] = !free_slide;
  return control;
}

void declare_stages(Teuchos::ParameterList& loading)
{
  parameters::declare_sublist(loading, "Stages",
                              "with 'type' = stages: the load path, one sublist per stage in the order they run, "
                              "named as curve.csv's stage column shall name it, each with 'kind' (rotate, lift, slide "
                              "x, lift force, slide x force), 'target' [deg, nm or nN], and optionally 'relative', "
                              "'Steps', 'free lift' (rotate, slide x, slide x force), 'free slide' (lift, lift "
                              "force), 'checkpoints' (rotate), 'stop at force' (lift, slide x)");
}

std::vector<Stage> read_stages(const Teuchos::ParameterList& list)
{
  constexpr int most_stages = 100;
  std::vector<Stage> stages;
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string key = "Loading/Stages/" + list.name(it);
    if (!list.entry(it).isList())
      throw parameters::InputError("parameter '" + key + "': each entry of 'Loading/Stages' is a stage (a sublist)");
    auto user = list.sublist(list.name(it));
    for (const char* required : {"kind", "target"})
      if (!user.isParameter(required))
        throw parameters::InputError("stage '" + key + "' has no '" + required + "' (" +
                                     (std::string(required) == "kind" ? "rotate, lift, slide x, lift force or slide x force"
                                                                      : "where it ends") + ")");
    const auto& kind_name = user.isType<std::string>("kind") ? user.get<std::string>("kind") : std::string();
    const auto kind = parameters::choice_named<StageKind>(kind_name, stage_kinds());
    if (!kind)
      throw parameters::InputError("parameter '" + key + "/kind' = '" + parameters::shorten(kind_name) +
                                   "': allowed kinds are rotate, lift, slide x, lift force, slide x force");
    parameters::validate(user, valid_stage(*kind), key);
    Stage stage;
    stage.kind = *kind;
    stage.name = list.name(it);
    stage.target = user.get<double>("target");
    stage.relative = user.get<bool>("relative");
    stage.steps = analysis::StepParameters::from(user.sublist("Steps"), key + "/Steps");
    if (user.isParameter("free lift")) stage.free_lift = user.get<bool>("free lift");
    if (user.isParameter("free slide")) stage.free_slide = user.get<bool>("free slide");
    if (user.isParameter("checkpoints")) stage.checkpoints = user.get<bool>("checkpoints");
    if (user.isParameter("stop at force")) stage.stop_at_force = user.get<double>("stop at force");
    if (stage.name.empty() || stage.name.find_first_of(",\n\"") != std::string::npos)
      throw parameters::InputError("stage '" + key + "': a stage's name is a column of curve.csv: not empty, and no "
                                   "comma, quote or line break");
    stages.push_back(stage);
    if (int(stages.size()) > most_stages)
      throw parameters::InputError("'Loading/Stages' has more than " + std::to_string(most_stages) + " stages");
  }
  if (stages.empty())
    throw parameters::InputError("'Loading/type' = stages needs at least one stage in 'Loading/Stages' (a sublist "
                                 "with 'kind' and 'target')");
  return stages;
}

}  // namespace spatula::app
