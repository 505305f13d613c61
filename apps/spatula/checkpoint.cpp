#include "checkpoint.hpp"
#include "pull_directions.hpp"

#include "discretization/system_fields.hpp"
#include "io/checked_write.hpp"

#include "io/hdf5_file.hpp"
#include "parameters/parameter_validation.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

namespace spatula::app {

namespace {

// What a checkpoint must agree with, each entry with the name a message gives it.
struct SignatureEntry {
  const char* name;
  double value;
};

std::vector<SignatureEntry> signature(const discretization::NodeSpace& nodes, const Scene& scene)
{
  const auto& g = scene.geometry;
  return {{"nodes (mesh and enrichment; 'Mesh/level', 'Mesh/refinement factor', 'Mesh/layers')",
           static_cast<double>(nodes.node_count())},
          {"Hex8 elements", static_cast<double>(nodes.hex8_elements.size())},
          {"Hex13 elements ('Adhesion/enrichment')", static_cast<double>(nodes.hex13_elements.size())},
          {"nodes per contact face ('Adhesion/enrichment')", static_cast<double>(nodes.face_nodes)},
          {"Geometry/a_s", g.a_s}, {"Geometry/b_s", g.b_s}, {"Geometry/c_s", g.c_s}, {"Geometry/l_s", g.l_s},
          {"Geometry/l_p", g.l_p}, {"Geometry/h_p", g.h_p}, {"Geometry/h_r", g.h_r}, {"Geometry/w_p", g.w_p},
          {"Geometry/r1", g.r1}, {"Geometry/r2", g.r2}, {"Geometry/r3", g.r3}, {"Geometry/r4", g.r4}};
}

std::vector<SignatureEntry> material_signature(const Scene& scene)
{
  return {{"Material/E", scene.material.young}, {"Material/nu", scene.material.poisson}};
}

std::vector<double> values(const std::vector<SignatureEntry>& entries)
{
  std::vector<double> v;
  for (const auto& entry : entries) v.push_back(entry.value);
  return v;
}

std::string number(double value)
{
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

std::vector<double> history(const analysis::LoadPoint& p)
{
  return {static_cast<double>(p.step), p.rotation, p.lift, p.slide, p.external_work, p.dissipated};
}

// The end-face masters of state x (written beside its displacements), and x set back from both.
std::vector<double> masters_of(const discretization::DiscreteSystem& system, const discretization::Vector& x)
{
  std::vector<double> masters;
  for (int m = 0; m < discretization::master_count; ++m) masters.push_back(system.master(x, discretization::Master(m)));
  return masters;
}

void set_state(const discretization::DiscreteSystem& system, const std::vector<double>& displacements,
               const std::vector<double>& masters, discretization::Vector& x)
{
  discretization::set_space_displacements(system, x, displacements);
  for (int m = 0; m < discretization::master_count; ++m) system.set_master(x, discretization::Master(m), masters[m]);
}

// The masters stored in `in`'s checkpoint `group` for this scene: a checkpoint made with another 'Loading/pull angle'
// (none stored: 90 deg) has its lift and slide turned into this scene's directions (the same face position).
std::vector<double> scene_masters(io::Hdf5File& in, const std::string& group, const std::string& dataset,
                                  const Scene& scene)
{
  auto masters = in.read_doubles(group + "/" + dataset);
  const double stored = in.exists(group + "/pull angle") ? in.read_doubles(group + "/pull angle").at(0) : 90.0;
  if (stored == scene.loading.pull_angle || masters.size() != discretization::master_count) return masters;
  const auto from = PullDirections::at(stored), to = PullDirections::at(scene.loading.pull_angle);
  const double lift = masters[1], slide = masters[2];
  const double x = from.x(lift, slide), z = from.z(lift, slide);
  masters[1] = to.along_lift(x, z);
  masters[2] = to.along_slide(x, z);
  return masters;
}

// A restart whose contact anchors are set at the restart state (not a resumed run, which has its own): a contact
// law with state then starts there with no tangential traction, its history cleared.
bool starts_relaxed(const Scene& scene) { return scene.adhesion.settings.anchor_at_restart && !scene.resume; }

std::string restart_key(const Scene& scene)
{
  return "parameter 'Loading/restart file' = '" + scene.loading.restart_file + "'";
}

}  // namespace

std::string checkpoint_label(double theta_y_degrees)
{
  std::ostringstream label;
  label << "theta_y=" << std::round(theta_y_degrees * 1000.0) / 1000.0;
  return label.str();
}

std::string restart_label(const LoadingParameters& loading)
{
  return loading.restart_from_last_state ? last_state_label : checkpoint_label(loading.restart_theta_y);
}

void write_checkpoint(const std::string& file, const std::string& label, const discretization::DiscreteSystem& system,
                      const discretization::Vector& x, const analysis::LoadPoint& point, const PathStage& stage,
                      const Scene& scene, const RunRecord& record, const discretization::Vector* anchors,
                      const analysis::LoadPath::JumpInProgress* jump)
{
  const auto displacements = discretization::space_displacements(system, x);   // collective
  const auto anchor_displacements =
      anchors ? discretization::space_displacements(system, *anchors) : std::vector<double>{};
  const auto jump_displacements =
      jump ? discretization::space_displacements(system, *jump->state) : std::vector<double>{};
  const auto masters = masters_of(system, x);
  const auto contact_history = system.contact_history();   // collective
  const auto jump_masters = jump ? masters_of(system, *jump->state) : std::vector<double>{};
  if (system.owned_map()->getComm()->getRank() != 0) return;
  namespace fs = std::filesystem;
  const std::string writing = file + ".writing";
  const bool exists = fs::exists(file);
  // A failed write (a full disk) leaves the checkpoints file as it was, without the half-written copy beside it.
  struct RemoveUnlessRenamed {
    const std::string& path;
    bool renamed = false;
    ~RemoveUnlessRenamed()
    {
      std::error_code ignored;
      if (!renamed) fs::remove(path, ignored);
    }
  } copy{writing};
  if (exists) fs::copy_file(file, writing, fs::copy_options::overwrite_existing);
  {
    io::Hdf5File out(writing, exists ? io::Hdf5File::Mode::append : io::Hdf5File::Mode::create);
    const std::string group = "/checkpoints/" + label;
    if (out.exists(group + "/displacements")) {
      if (label != last_state_label) return;   // already taken (a restarted run passing it again)
      out.remove(group);
    }
    out.write(group + "/displacements", displacements, 3);
    out.write(group + "/masters", masters);
    out.write(group + "/pull angle", std::vector<double>{scene.loading.pull_angle});
    if (anchors) out.write(group + "/anchors", anchor_displacements, 3);
    if (!contact_history.empty()) out.write(group + "/contact history", contact_history);
    if (jump) {
      out.write(group + "/jump displacements", jump_displacements, 3);
      out.write(group + "/jump masters", jump_masters);
      out.write(group + "/jump", std::vector<double>{static_cast<double>(jump->controlled), jump->value, jump->shift,
                                                     jump->scale, static_cast<double>(jump->iterations)});
    }
    out.write(group + "/history", history(point));
    out.write(group + "/stage", std::vector<double>{static_cast<double>(stage.index), stage.start});
    out.write(group + "/signature", values(signature(system.nodes(), scene)));
    out.write(group + "/material", values(material_signature(scene)));
    const auto& curve = record.step_control.curve;
    out.write(group + "/run", std::vector<double>{record.initial_internal_energy, record.initial_contact_energy,
                                                  record.peak_moment, record.peak_force, record.seconds,
                                                  static_cast<double>(record.field_states),
                                                  record.step_control.increment, record.step_control.failed_load,
                                                  record.step_control.failed_known ? 1.0 : 0.0,
                                                  record.step_control.bisecting ? 1.0 : 0.0, curve.load[0],
                                                  curve.load[1], curve.load[2], curve.reaction[0], curve.reaction[1],
                                                  curve.reaction[2], static_cast<double>(curve.count),
                                                  static_cast<double>(curve.step), curve.largest});
    out.close();
  }
  io::rename_path(writing, file);
  copy.renamed = true;
}

bool holds_checkpoint(const std::string& file, const std::string& label)
{
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) return false;
  try {
    io::Hdf5File in(file, io::Hdf5File::Mode::read);
    return in.exists("/checkpoints/" + label + "/displacements");
  } catch (const std::exception&) {
    return false;
  }
}

bool resumable(const std::string& file)
{
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) return false;
  try {
    io::Hdf5File in(file, io::Hdf5File::Mode::read);
    const std::string group = std::string("/checkpoints/") + last_state_label;
    return in.exists(group + "/displacements") && in.exists(group + "/run");
  } catch (const std::exception&) {
    return false;
  }
}

bool holds_anchors(const std::string& file)
{
  try {
    io::Hdf5File in(file, io::Hdf5File::Mode::read);
    return in.exists(std::string("/checkpoints/") + last_state_label + "/anchors");
  } catch (const std::exception&) {
    return false;
  }
}

void read_anchors(const Scene& scene, const discretization::DiscreteSystem& system, discretization::Vector& anchors)
{
  io::Hdf5File in(scene.loading.restart_file, io::Hdf5File::Mode::read);
  discretization::set_space_displacements(
      system, anchors, in.read_doubles("/checkpoints/" + restart_label(scene.loading) + "/anchors"));
}

RunRecord read_run_record(const Scene& scene)
{
  io::Hdf5File in(scene.loading.restart_file, io::Hdf5File::Mode::read);
  const auto r = in.read_doubles("/checkpoints/" + restart_label(scene.loading) + "/run");
  // 10 values, or 19 with the curve's samples (CurveResolution)
  if (r.size() != 10 && r.size() != 19)
    throw std::runtime_error(restart_key(scene) + ": the checkpoint has no run record");
  analysis::StepControllerState control{r[6], r[7], r[8] != 0.0, r[9] != 0.0, {}};
  if (r.size() == 19) {
    auto& curve = control.curve;
    for (int k = 0; k < 3; ++k) {
      curve.load[k] = r[10 + k];
      curve.reaction[k] = r[13 + k];
    }
    curve.count = static_cast<int>(r[16]);
    curve.step = static_cast<int>(r[17]);
    curve.largest = r[18];
  }
  return {r[0], r[1], r[2], r[3], r[4], static_cast<int>(r[5]), control};
}

std::optional<analysis::LoadPath::JumpInProgress> read_jump_in_progress(const Scene& scene,
                                                                       const discretization::DiscreteSystem& system)
{
  io::Hdf5File in(scene.loading.restart_file, io::Hdf5File::Mode::read);
  const std::string group = "/checkpoints/" + restart_label(scene.loading);
  if (!in.exists(group + "/jump")) return std::nullopt;
  const auto j = in.read_doubles(group + "/jump");
  const auto masters = scene_masters(in, group, "jump masters", scene);
  if (j.size() != 5 || masters.size() != discretization::master_count)
    throw parameters::InputError(restart_key(scene) + ": the jump stored with checkpoint '" +
                                 restart_label(scene.loading) + "' is incomplete");
  analysis::LoadPath::JumpInProgress jump;
  jump.controlled = discretization::Master(static_cast<int>(j[0]));
  jump.value = j[1];
  jump.shift = j[2];
  jump.scale = j[3];
  jump.iterations = static_cast<int>(j[4]);
  jump.state = system.create_vector();
  set_state(system, in.read_doubles(group + "/jump displacements"), masters, *jump.state);
  return jump;
}

void check_checkpoint(const Scene& scene, const discretization::NodeSpace& nodes)
{
  const auto& file = scene.loading.restart_file;
  if (file.empty()) return;
  std::error_code error;
  if (!std::filesystem::exists(file, error)) throw parameters::InputError(restart_key(scene) + ": no such file");
  if (!std::filesystem::is_regular_file(file, error))
    throw parameters::InputError(restart_key(scene) + ": not a regular file");
  std::unique_ptr<io::Hdf5File> in;
  try {
    in = std::make_unique<io::Hdf5File>(file, io::Hdf5File::Mode::read);
  } catch (const std::exception&) {
    throw parameters::InputError(restart_key(scene) + ": not an HDF5 file (give the checkpoints.h5 of an earlier run)");
  }
  const std::string label = restart_label(scene.loading);
  const std::string group = "/checkpoints/" + label;
  const char* selector = scene.loading.restart_from_last_state ? "'Loading/restart from' = 'last state'"
                                                               : "'Loading/restart theta_y'";
  if (!in->exists(group + "/displacements") || !in->exists(group + "/signature"))
    throw parameters::InputError(restart_key(scene) + " has no checkpoint '" + label + "' (asked for by " + selector +
                                 ")");
  auto compare = [&](const std::string& dataset, const std::vector<SignatureEntry>& expected) {
    const auto stored = in->read_doubles(group + "/" + dataset);
    if (stored.size() != expected.size())
      throw parameters::InputError(restart_key(scene) + ": checkpoint '" + label + "' is not one this program wrote");
    std::string mismatches;
    for (std::size_t i = 0; i < expected.size(); ++i)
      if (stored[i] != expected[i].value)
        mismatches += std::string(mismatches.empty() ? "" : "; ") + expected[i].name + ": " + number(stored[i]) +
                      " in the checkpoint, " + number(expected[i].value) + " in this scene";
    if (!mismatches.empty())
      throw parameters::InputError(restart_key(scene) + ": checkpoint '" + label +
                                   "' was made for another scene (" + mismatches + ")");
  };
  compare("signature", signature(nodes, scene));
  if (in->exists(group + "/material")) compare("material", material_signature(scene));
  const auto stored_history = in->read_doubles(group + "/history");
  if (stored_history.size() < 5 || in->read_doubles(group + "/masters").size() != discretization::master_count ||
      in->read_doubles(group + "/displacements").size() != 3 * static_cast<std::size_t>(nodes.node_count()))
    throw parameters::InputError(restart_key(scene) + ": checkpoint '" + label + "' is incomplete");
  // A contact law with state goes on from the points' histories stored with the state, unless its anchors are set
  // at the restart state (then it starts there relaxed, as from the undeformed state).
  if (scene.adhesion.enabled && !starts_relaxed(scene)) {
    const auto& contact = scene.adhesion.model;
    const std::size_t order = contact->quadrature_order();
    const std::size_t points = nodes.faces.size() * order * order;
    const std::size_t stored =
        in->exists(group + "/contact history") ? in->read_doubles(group + "/contact history").size() : 0;
    if (contact->history_size() > 0 && contact->stored_history_width(stored, points) == 0)
      throw parameters::InputError(
          restart_key(scene) + ": checkpoint '" + label + "' holds no contact history for 'Adhesion/law' = '" +
          scene.adhesion.settings.law + "' with " + std::to_string(order) + " x " + std::to_string(order) +
          " points per face (it was written with another law or quadrature); a law with state goes on only from its "
          "own states, or from any with 'Adhesion/stiction anchors' = 'restart state' (it then starts there, relaxed)");
  }
  // Tangential tractions are measured from the stiction anchors: a state of a run that set them at its restart state
  // (stored with it) goes on with those (--resume) or with new ones at this state, never from the undeformed ones.
  if (scene.adhesion.enabled && scene.adhesion.model->holds_tangentially() &&
      !scene.adhesion.settings.anchor_at_restart && in->exists(group + "/anchors"))
    throw parameters::InputError(
        restart_key(scene) + ": checkpoint '" + label + "' was written by a run whose stiction anchors were set at "
        "its restart state, but this scene has 'Adhesion/stiction anchors' = 'undeformed': the checkpoint's tangential "
        "tractions and contact histories are measured from its own anchors. Resume that run (spatula --resume with its "
        "scene), or set the anchors anew at this state ('Adhesion/stiction anchors' = 'restart state': the pad starts "
        "there unstrained)");
  // The stage it lies in must be one of this scene's path (a scene without loading follows none).
  if (!scene.loading.stages.empty() && in->exists(group + "/stage")) {
    const auto stage = static_cast<int>(in->read_doubles(group + "/stage").at(0));
    const auto stages = static_cast<int>(scene.loading.stages.size());
    if (stage < 0 || stage >= stages)
      throw parameters::InputError(restart_key(scene) + ": checkpoint '" + label + "' lies in stage " +
                                   std::to_string(stage + 1) + " of its path, but this scene has " +
                                   std::to_string(stages) + " stage(s) ('Loading/type', 'Loading/Stages')");
  }
}

analysis::LoadPoint read_checkpoint(const Scene& scene, discretization::DiscreteSystem& system,
                                    discretization::Vector& x, PathStage& stage)
{
  io::Hdf5File in(scene.loading.restart_file, io::Hdf5File::Mode::read);
  const std::string group = "/checkpoints/" + restart_label(scene.loading);
  set_state(system, in.read_doubles(group + "/displacements"), scene_masters(in, group, "masters", scene), x);
  if (in.exists(group + "/contact history") && !starts_relaxed(scene))
    system.set_contact_history(in.read_doubles(group + "/contact history"));
  const auto h = in.read_doubles(group + "/history");
  analysis::LoadPoint point;
  point.step = static_cast<int>(h[0]);
  point.rotation = h[1];
  point.lift = h[2];
  point.slide = h[3];
  point.external_work = h[4];
  point.dissipated = h.size() > 5 ? h[5] : 0.0;
  stage = PathStage{};
  if (in.exists(group + "/stage")) {
    const auto s = in.read_doubles(group + "/stage");
    stage.index = static_cast<int>(s.at(0));
    stage.start = s.at(1);
  }
  return point;
}

}  // namespace spatula::app
