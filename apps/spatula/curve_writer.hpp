#pragma once
// curve.csv: one row per converged state, full-spatula values (the model is half of it).
// Energies in the paper's form: Pi_sa = Pi_c - Pi_c(start) (= Pi_c0 + Pi_c for the exact law), all over
// Pi_c0 = A_c w_adh; the balance error |Pi_ext - Pi_int - Pi_sa| / Pi_c0 (Pi_c0 = 1 without adhesion).
#include "analysis/load_stepping.hpp"
#include "full_spatula.hpp"
#include "pull_directions.hpp"

#include <fstream>
#include <string>

namespace spatula::app {

class CurveWriter {
public:
  // Energies are counted from a baseline state: the undeformed spatula, or (rough substrates) the pad pressed
  // onto the substrate, whose internal and adhesion energies are given here.
  // `resume_after`: go on with the curve of a stopped run, keeping its rows up to that step (-1: a new curve).
  // `directions`: the end face's lift and slide directions, whose motions and forces the curve reports in Z and X.
  CurveWriter(const std::string& file, double young, double reference_energy, double initial_internal_energy,
              double initial_contact_energy, int resume_after = -1, PullDirections directions = {});
  double stored_adhesion(const analysis::LoadPoint& p) const { return full_spatula(p.contact_energy - initial_contact_); }
  double internal(const analysis::LoadPoint& p) const { return full_spatula(p.internal_energy - initial_internal_); }
  // The face centre's displacement and the net force on the face (full spatula) in the substrate's Z and X.
  double u_z(const analysis::LoadPoint& p) const { return directions_.z(p.lift, p.slide); }
  double u_x(const analysis::LoadPoint& p) const { return directions_.x(p.lift, p.slide); }
  double P_z(const analysis::LoadPoint& p) const { return full_spatula(directions_.z(p.force, p.slide_force)); }
  double P_x(const analysis::LoadPoint& p) const { return full_spatula(directions_.x(p.force, p.slide_force)); }
  // |Pi_ext - Pi_int - Pi_sa - D| / Pi_c0 with D the energy dissipated: released by the jumps past instabilities
  // and, with a friction law, by sliding.
  double balance_error(const analysis::LoadPoint& p) const;
  // One row; `stage` is the stage's name, `theta_s` the shaft's inclination in the undeformed state [rad].
  void write(const analysis::LoadPoint& p, const std::string& stage, double theta_s);

private:
  // The rows written so far reach the file, or the curve is cut back to its last whole row (a full disk leaves a
  // readable curve up to the last state that fitted) and the write failure is thrown.
  void commit_row();
  // Rewrites the curve with its header and the rows of steps up to `last_step` (a stopped run's rows past its
  // checkpoint are computed again).
  static void keep_rows_up_to(const std::string& file, int last_step);

  std::string file_;
  std::ofstream out_;
  std::streamoff written_ = -1;   // bytes of the curve's whole rows in the file
  double young_, reference_, initial_internal_, initial_contact_;
  PullDirections directions_;
};

}  // namespace spatula::app
