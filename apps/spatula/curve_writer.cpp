#include "curve_writer.hpp"

#include "io/checked_write.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

namespace spatula::app {

namespace {

constexpr double degree = 3.14159265358979323846 / 180.0;

}  // namespace

CurveWriter::CurveWriter(const std::string& file, double young, double reference_energy,
                         double initial_internal_energy, double initial_contact_energy, int resume_after,
                         PullDirections directions)
    : file_(file), young_(young), reference_(reference_energy), initial_internal_(initial_internal_energy),
      initial_contact_(initial_contact_energy), directions_(directions)
{
  if (resume_after >= 0) {
    keep_rows_up_to(file, resume_after);
    written_ = static_cast<std::streamoff>(std::filesystem::file_size(file));
    out_.open(file, std::ios::app);
    io::check_written(out_, file_);
    out_ << std::setprecision(10);
    return;
  }
  out_.open(file);
  out_ << "step,stage,theta_y_deg,u_z_nm,M_y_nNnm,M_y_per_ER0^3,P_z_nN,P_z_per_ER0^2,Pi_int_1e-18J,"
          "Pi_ext_1e-18J,Pi_c_1e-18J,Pi_sa_1e-18J,Pi_ext_per_Pi_c0,Pi_int_per_Pi_c0,Pi_sa_per_Pi_c0,"
          "dissipated_per_Pi_c0,balance_error_per_Pi_c0,after_jump,contact_faces_active,contact_faces_skipped,"
          "newton_iterations,negative_pivots,wall_s,u_x_nm,P_x_nN\n";
  commit_row();
  out_ << std::setprecision(10);
}

double CurveWriter::balance_error(const analysis::LoadPoint& p) const
{
  const auto full = full_spatula(p);
  return std::abs(full.external_work - internal(p) - stored_adhesion(p) - full.dissipated) / reference_;
}

void CurveWriter::write(const analysis::LoadPoint& p, const std::string& stage, double theta_s)
{
  const double sa = stored_adhesion(p);
  const auto full = full_spatula(p);
  out_ << p.step << "," << stage << "," << (theta_s + p.rotation) / degree << "," << u_z(p) << ","
       << full.moment << "," << full.moment / young_ << "," << P_z(p) << "," << P_z(p) / young_ << ","
       << internal(p) << "," << full.external_work << "," << full.contact_energy << "," << sa << ","
       << full.external_work / reference_ << "," << internal(p) / reference_ << "," << sa / reference_
       << "," << full.dissipated / reference_ << "," << balance_error(p) << "," << (p.after_jump ? 1 : 0) << ","
       << p.active_faces << "," << p.skipped_faces << ","
       << p.newton_iterations << "," << p.negative_pivots << "," << p.seconds << "," << u_x(p) << "," << P_x(p) << "\n";
  commit_row();
}

void CurveWriter::commit_row()
{
  try {
    io::check_written(out_, file_);
    written_ = out_.tellp();   // the end of the file once a row has been written (opened to append)
  } catch (...) {
    std::error_code ignored;
    if (written_ >= 0) std::filesystem::resize_file(file_, static_cast<std::uintmax_t>(written_), ignored);
    throw;
  }
}

void CurveWriter::keep_rows_up_to(const std::string& file, int last_step)
{
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot resume: '" + file + "' is missing");
  std::string line, kept;
  for (bool header = true; std::getline(in, line); header = false)
    if (header || (!line.empty() && std::stoi(line.substr(0, line.find(','))) <= last_step)) kept += line + "\n";
  in.close();
  io::write_text_file(file + ".writing", kept);
  io::rename_path(file + ".writing", file);
}

}  // namespace spatula::app
