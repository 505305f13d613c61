#pragma once
// The adhesion contribution to the system: the pad's contact faces integrated with a law and a substrate.
// DiscreteSystem calls `assemble` with this rank's faces and the scatter; IntegrandContactModel<Integrand> is the
// implementation for any device integrand (frictionless or stiction, flat or rough: see packages/contact, whose
// registry turns the XML choice into one of these).
#include "contact/contact_face.hpp"
#include "discretization/element_scatter.hpp"

#include <array>
#include <memory>
#include <string>

namespace spatula::discretization {

// This rank's contact faces on the device (local node ids; Quad4 faces use the first 4 columns).
struct ContactFaceViews {
  Kokkos::View<const int* [9], device_type> nodes;
  Kokkos::View<const double*, device_type> areas;      // undeformed area of each face
  Kokkos::View<const double* [3], device_type> coordinates;   // reference positions of the local nodes
  Kokkos::View<const double* [3], device_type> anchors;       // where the stiction law measures travel from
  // A law with state (ContactModel::history_size() > 0): per face, per quadrature point (a, b) at a order + b, its
  // history values; `history` the committed state's, `trial_history` written by every assembly (empty: no state).
  Kokkos::View<const double*, device_type> history;
  Kokkos::View<double*, device_type> trial_history;
  int face_nodes = 4;
  int count = 0;
};

struct ContactTotals {
  double energy = 0.0;       // Pi_c of this rank's faces [nN nm]
  int active_faces = 0;      // faces integrated (some point within the cut-off)
  int skipped_faces = 0;     // faces certainly beyond the cut-off: not integrated
  int active_points = 0;     // quadrature points within the cut-off
  double dissipated = 0.0;   // a law with state: energy dissipated up to the evaluated state [nN nm]
};

// The contact points a Newton step carries across the law's inflection (its strongest attraction, where its stiffness
// changes sign): the peel front's limiting points. Their count, where they sit in the reference configuration (the
// mean and spread of X and Y) and their share of the change of Pi_c along the step; and the count of points whose
// gap changes by more than a given fraction of r0; and how far the points still adhering at the end have slid.
struct GapChanges {
  int crossing = 0;
  int large = 0;
  double mean[2] = {0.0, 0.0}, spread[2] = {0.0, 0.0};   // X and Y of the crossing points [nm]
  double energy_change[4] = {0.0, 0.0, 0.0, 0.0};        // at t = 0.25, 0.5, 0.75 and 1 of the step [nN nm]
  double adhering_area = 0.0;   // undeformed area of the points still adhering at the end [nm^2]
  double mean_slip = 0.0;       // their mean travel along the substrate's plane [nm] (0 without such points)
};
// The peel front's points a step would release, for a step that limits their gap change (DiscreteSystem::
// contact_gap_limit): their count and the target t of the row c . du = t.
struct GapLimit {
  int points = 0;
  double target = 0.0;   // [nm^3]
};
using contact::gap_change_sums;   // what ContactModel::gap_changes sums (contact_face.hpp: face_gap_changes)
using contact::gap_limit_sums;    // what ContactModel::gap_limit sums (contact_face.hpp: face_gap_limit)

class ContactModel {
public:
  virtual ~ContactModel() = default;
  virtual std::string description() const = 0;
  virtual double work_of_adhesion() const = 0;   // w_adh = -phi(r_eq) of the law [nN/nm]
  virtual int quadrature_order() const = 0;
  // A law with state (adhesive friction): the history values per quadrature point, committed by the caller at
  // converged states (DiscreteSystem::commit_contact_history); 0: none.
  virtual int history_size() const { return 0; }
  // The values per point of a stored history of `stored` values over `points` quadrature points: history_size(), or
  // one fewer for a history written before the law's last value was added (read with that value 0); 0 for neither.
  std::size_t stored_history_width(std::size_t stored, std::size_t points) const
  {
    const auto size = static_cast<std::size_t>(history_size());
    return stored == points * size ? size : size > 1 && stored == points * (size - 1) ? size - 1 : 0;
  }
  // Where such a history keeps the energy dissipated at the point [nN/nm]; -1: it keeps none.
  virtual int dissipated_index() const { return -1; }
  // A traction along the substrate (stiction, friction): the law holds the pad there, so an end face free to move
  // along the substrate is not a singular system.
  virtual bool holds_tangentially() const { return false; }
  // false: the tangent is not symmetric (a sliding limit that depends on the gap); the linear solver factors LU.
  virtual bool symmetric() const { return true; }
  // The law a jump's energy descent assembles instead of this one, on the same history (a law whose gradient is not
  // that of an energy: the return mapping of adhesive friction); null: this one.
  virtual std::shared_ptr<const ContactModel> descent_law() const { return nullptr; }
  virtual ContactTotals assemble(const ContactFaceViews& faces, const ElementScatter& scatter) const = 0;
  // This rank's sums of face_gap_changes (contact_face.hpp) from the state of `from` to that of `to` (the
  // scatters' displacements), a gap change above `fraction` r0 counting as large: crossing and large points, the
  // crossing points' sums of X, Y, X^2, Y^2 and their share of Pi_c's change at t = 0.25, 0.5, 0.75, 1.
  virtual std::array<double, gap_change_sums> gap_changes(const ContactFaceViews& faces, const ElementScatter& from,
                                            const ElementScatter& to, double fraction) const = 0;
  // The row c of the points the step from `from` to `to` carries outward past the law's inflection + `beyond` (nm),
  // scattered into the residual of `from`, and this rank's sums of their count and target t (face_gap_limit).
  virtual std::array<double, gap_limit_sums> gap_limit(const ContactFaceViews& faces, const ElementScatter& from,
                                                       const ElementScatter& to, double beyond) const = 0;
};

}  // namespace spatula::discretization
