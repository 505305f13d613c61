#include "checkpoint.hpp"

#include "hdf5_file.hpp"
#include "parameter_validation.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

namespace spatula::app {

namespace {

std::vector<double> signature(const discretization::DiscreteSystem& system, const Scene& scene)
{
  const auto& g = scene.geometry;
  return {static_cast<double>(system.nodes().node_count()), static_cast<double>(system.nodes().hex8_elements.size()),
          static_cast<double>(system.nodes().hex13_elements.size()), static_cast<double>(system.nodes().face_nodes),
          g.a_s, g.b_s, g.c_s, g.l_s, g.l_p, g.h_p, g.h_r, g.w_p, g.r1, g.r2, g.r3, g.r4};
}

std::vector<double> history(const analysis::LoadPoint& p)
{
  return {static_cast<double>(p.step), p.rotation, p.lift, p.slide, p.external_work, p.dissipated};
}

}  // namespace

std::string checkpoint_label(double theta_y_degrees)
{
  std::ostringstream label;
  label << "theta_y=" << std::round(theta_y_degrees * 1000.0) / 1000.0;
  return label.str();
}

void write_checkpoint(const std::string& file, double theta_y_degrees, const discretization::DiscreteSystem& system,
                      const discretization::Vector& x, const analysis::LoadPoint& point, const Scene& scene)
{
  const auto displacements = system.space_displacements(x);   // collective
  std::vector<double> masters;
  for (int m = 0; m < discretization::master_count; ++m) masters.push_back(system.master(x, discretization::Master(m)));
  if (system.owned_map()->getComm()->getRank() != 0) return;
  const bool exists = std::filesystem::exists(file);
  io::Hdf5File out(file, exists ? io::Hdf5File::Mode::append : io::Hdf5File::Mode::create);
  const std::string group = "/checkpoints/" + checkpoint_label(theta_y_degrees);
  if (out.exists(group + "/displacements")) return;   // already taken (a restarted run passing it again)
  out.write(group + "/displacements", displacements, 3);
  out.write(group + "/masters", masters);
  out.write(group + "/history", history(point));
  out.write(group + "/signature", signature(system, scene));
}

analysis::LoadPoint read_checkpoint(const std::string& file, double theta_y_degrees,
                                    const discretization::DiscreteSystem& system, discretization::Vector& x,
                                    const Scene& scene)
{
  if (!std::filesystem::exists(file))
    throw parameters::InputError("parameter 'Loading/restart file' = '" + file + "': no such file");
  io::Hdf5File in(file, io::Hdf5File::Mode::read);
  const std::string label = checkpoint_label(theta_y_degrees);
  const std::string group = "/checkpoints/" + label;
  if (!in.exists(group + "/displacements"))
    throw parameters::InputError("parameter 'Loading/restart theta_y' = " + std::to_string(theta_y_degrees) +
                                 ": file '" + file + "' has no checkpoint " + label);
  if (in.read_doubles(group + "/signature") != signature(system, scene))
    throw parameters::InputError("checkpoint " + label + " in '" + file +
                                 "' was made for another geometry, mesh or enrichment than this scene's");
  system.set_space_displacements(x, in.read_doubles(group + "/displacements"));
  const auto masters = in.read_doubles(group + "/masters");
  for (int m = 0; m < discretization::master_count; ++m) system.set_master(x, discretization::Master(m), masters[m]);
  const auto h = in.read_doubles(group + "/history");
  analysis::LoadPoint point;
  point.step = static_cast<int>(h[0]);
  point.rotation = h[1];
  point.lift = h[2];
  point.slide = h[3];
  point.external_work = h[4];
  point.dissipated = h.size() > 5 ? h[5] : 0.0;
  return point;
}

}  // namespace spatula::app
