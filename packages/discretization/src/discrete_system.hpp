#pragma once
// The distributed nonlinear system of the spatula: assembly of the residual and the consistent tangent by labelled
// Kokkos kernels over each rank's elements and contact faces (FECrsMatrix / FEMultiVector fill, shared rows summed at
// endFill), on what a rank holds (its maps, the FE graph built once, the device views: system_topology.hpp). The
// state as fields over the mesh: system_fields.hpp.
//
// Unknowns are displacements [nm] and the three end-face masters: rotation alpha [rad], lift w and slide s [nm].
// Residual rows are internal forces [nN] (the master rows: moment [nN nm] and forces on the face, half spatula).
// A prescribed master keeps an identity row and no coupling (its value lives in the state vector); its internal
// force is returned as the reaction.
#include "discretization/contact_model.hpp"
#include "discretization/dof_layout.hpp"
#include "discretization/solid_model.hpp"
#include "discretization/rigid_face.hpp"
#include "discretization/tpetra_types.hpp"

#include <Teuchos_Comm.hpp>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <array>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

namespace spatula::discretization {

struct SystemTopology;

// Which end-face masters are prescribed (their values are then taken from the state vector).
struct MasterControl {
  std::array<bool, master_count> prescribed{true, true, true};
  // The dead load on each free master (moment [nN nm], lift and slide forces [nN], half model): its potential
  // -applied u joins Pi, its row of f is the reaction less it. Zero: the master is free of load.
  std::array<double, master_count> applied{};
  // `moved` prescribed, the masters in `free` left free (zero net reaction), the others held.
  static MasterControl moving(Master moved, std::initializer_list<Master> free = {})
  {
    MasterControl control;
    for (Master master : free)
      if (master != moved) control.prescribed[static_cast<int>(master)] = false;
    return control;
  }
};

struct Evaluation {
  bool admissible = true;          // false: an element inverted (J <= 0); residual and matrix are not usable
  std::int64_t inverted_element = -1;
  double internal_energy = 0.0;    // Pi_int of the half model [nN nm]
  double contact_energy = 0.0;     // Pi_c of the half model [nN nm] (0 without adhesion)
  double contact_dissipated = 0.0; // a contact law with state: energy dissipated up to this state (half) [nN nm]
  int active_contact_faces = 0;    // contact faces integrated (all ranks)
  int skipped_contact_faces = 0;   // contact faces beyond the cut-off, not integrated
  std::array<double, master_count> master_residual{};   // moment [nN nm], lift and slide forces [nN] (half)
  double load_potential = 0.0;     // -applied . u over the free masters with a dead load [nN nm] (0 without)
  // Pi = Pi_int + Pi_c (+ the dead loads' potential), whose gradient is f
  double energy() const { return internal_energy + contact_energy + load_potential; }
};

// What the system contains besides the solid: the contact enrichment and an adhesion model (none: no contact).
struct SystemOptions {
  Enrichment enrichment = Enrichment::q1c1;
  std::shared_ptr<const ContactModel> contact;
};

class DiscreteSystem {
public:
  DiscreteSystem(const mesh::HexMesh& mesh, const mesh::Partition& partition, const Constraints& constraints,
                 const SolidParameters& solid, Teuchos::RCP<const Teuchos::Comm<int>> comm,
                 const SystemOptions& options = {});
  ~DiscreteSystem();

  Teuchos::RCP<const Map> owned_map() const;
  Teuchos::RCP<Vector> create_vector() const;   // zero state = the undeformed spatula
  Teuchos::RCP<CrsMatrix> jacobian() const;    // the FE matrix the assembly fills
  const DofLayout& layout() const;
  const NodeSpace& nodes() const;
  // Undeformed contact area of the half model (sum over the contact faces) [nm^2].
  double contact_area() const;

  void set_control(const MasterControl& control);
  const MasterControl& control() const;
  // Value of a master unknown in x (same on all ranks), and setting it (the owner writes).
  double master(const Vector& x, Master which) const;
  void set_master(Vector& x, Master which, double value) const;

  // Assembles what is asked: the residual (if non-null), the tangent into jacobian() (if `with_jacobian`).
  Evaluation evaluate(const Vector& x, Vector* residual, bool with_jacobian);

  // After an evaluation with the tangent: column m holds d f / d(master m) for the prescribed masters (zero for
  // free ones): the load vector of a continuation in that master.
  const MultiVector& load_derivatives() const;

  // Anchors the contact law at the state x: a law that measures tangential travel (stiction) measures it from the
  // nodes' positions in x from now on, instead of from the undeformed spatula. Collective.
  void set_contact_anchors(const Vector& x);
  // A contact law with state (ContactModel::history_size() > 0): the state x is converged, its points' histories
  // become the committed ones that the next evaluations start from. false: no such law, nothing done. Collective.
  bool commit_contact_history(const Vector& x);
  // The committed histories of all contact faces, face after face in the order of nodes().faces (every rank gets
  // them; empty without a law with state), and setting them from such an array (a restart). Collective.
  std::vector<double> contact_history() const;
  void set_contact_history(const std::vector<double>& all);
  // The contact points whose gap crosses the law's inflection, or changes by more than `fraction` r0, from the state
  // `from` to the state `to`, and the mean slip of those adhering at `to` (all ranks; none without adhesion).
  // Collective.
  GapChanges contact_gap_changes(const Vector& from, const Vector& to, double fraction);
  // The points the step from `from` to `to` carries outward past the law's inflection + `beyond` (nm): into `row`
  // the integral of their gap's gradient (zero at prescribed masters), and their count and target, the integral of
  // (limit - gap at `from`): c . du = t brings them, in the integral, to the limit (all ranks). Collective.
  GapLimit contact_gap_limit(const Vector& from, const Vector& to, double beyond, Vector& row);
  // Mean absolute diagonal of the last assembled tangent (the scale of the energy descent's shift).
  double mean_diagonal() const;

  // What one rank holds (elements, maps, graph, device views) and the solid's parameters: for the fields of
  // system_fields.hpp and diagnostics.
  const SystemTopology& topology() const;
  const SolidParameters& solid() const;
  const SolidModel& solid_model() const;   // the law 'Material/law' names
  const ContactModel* contact_model() const;   // the adhesion law (nullptr: no contact)
  // While true, the contact faces are assembled with the law's descent law (ContactModel::descent_law), where it
  // has one, on the same history: what a jump's energy descent minimizes. contact_model() then returns it.
  void use_descent_law(bool on);
  bool has_descent_law() const;

private:
  struct Implementation;
  std::unique_ptr<Implementation> implementation_;
};

// The contact law's descent law assembled while it lives (DiscreteSystem::use_descent_law), the law's own after.
class DescentLawScope {
public:
  explicit DescentLawScope(DiscreteSystem& system) : system_(system) { system_.use_descent_law(true); }
  ~DescentLawScope() { system_.use_descent_law(false); }
  DescentLawScope(const DescentLawScope&) = delete;
  DescentLawScope& operator=(const DescentLawScope&) = delete;

private:
  DiscreteSystem& system_;
};

}  // namespace spatula::discretization
