#pragma once
// The discrete system's private part, shared by its two source files (discrete_system.cpp: construction, evaluation
// and the masters; discrete_system_contact.cpp: the contact faces' anchors, history and gap measures): the topology's
// elements and faces assembled into the FE matrix and vectors it was built for.
#include "discretization/discrete_system.hpp"
#include "discretization/system_topology.hpp"

#include "discretization/solid_kernel.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Assembly_Helpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <array>
#include <stdexcept>
#include <string>

namespace spatula::discretization {

namespace detail {

// Adds `value` to the diagonal of each row in the range but the `skip`ped ones: the identity rows of prescribed
// masters. A named functor, not a lambda: CUDA cannot compile a device lambda inside the private
// DiscreteSystem::Implementation.
struct AddToDiagonal {
  CrsMatrix::local_matrix_device_type matrix;
  Kokkos::View<const int*, device_type> column_of;
  double value;
  int skip[master_count];

  KOKKOS_INLINE_FUNCTION void operator()(const int row) const
  {
    for (int m = 0; m < master_count; ++m)
      if (row == skip[m]) return;
    const int column = column_of(row);
    matrix.sumIntoValues(row, &column, 1, &value, false, true);
  }
};

}  // namespace detail

struct DiscreteSystem::Implementation : SystemTopology {
  SolidParameters solid;
  std::shared_ptr<const SolidModel> solid_model;
  SystemOptions options;
  MasterControl control;

  Teuchos::RCP<FECrsMatrix> matrix;
  Teuchos::RCP<FEMultiVector> residual;
  Teuchos::RCP<FEMultiVector> coupling;       // d f / d(prescribed master), one column per master
  Teuchos::RCP<Vector> state;                 // on the overlap map
  Teuchos::RCP<Vector> other_state;           // a second one, for comparing two states (made when first needed)
  DeviceView<int[1]> dropped_entries;   // ElementScatter::dropped (made once Kokkos is up, with the views)
  DeviceView<double*> committed_history;   // contact_faces.history, writable (a contact law with state)
  std::shared_ptr<const ContactModel> law, descent_law;   // options.contact is one of them (use_descent_law)

  Implementation(const mesh::HexMesh& mesh_, const mesh::Partition& partition, const Constraints& constraints,
                 const SolidParameters& solid_, Teuchos::RCP<const Teuchos::Comm<int>> comm_,
                 const SystemOptions& options_)
      : SystemTopology(mesh_, partition, constraints, options_.enrichment, options_.contact != nullptr,
                       std::move(comm_)),
        solid(solid_), solid_model(SolidLawRegistry::instance().make(solid_)), options(options_), matrix(Teuchos::rcp(new FECrsMatrix(graph))),
        residual(Teuchos::rcp(new FEMultiVector(owned, graph->getImporter(), 1))),
        coupling(Teuchos::rcp(new FEMultiVector(owned, graph->getImporter(), master_count))),
        state(Teuchos::rcp(new Vector(overlap))), dropped_entries("dropped tangent entries")
  {
    law = options.contact;
    if (law) descent_law = law->descent_law();
    if (history_per_face() > 0) {   // every point starts from zero: the undeformed pad
      const std::size_t size = contact_faces.count * history_per_face();
      committed_history = DeviceView<double*>("contact history", size);
      contact_faces.history = committed_history;
      contact_faces.trial_history = DeviceView<double*>("contact trial history", size);
    }
  }

  // A contact law with state: its history values per face (0: none).
  std::size_t history_per_face() const
  {
    if (!options.contact) return 0;
    const std::size_t order = options.contact->quadrature_order();
    return order * order * options.contact->history_size();
  }

  ElementScatter make_scatter(const std::array<double, master_count>& masters, bool with_matrix)
  {
    ElementScatter scatter;
    scatter.column_of = column_of;
    scatter.node_unknown = node_unknown;
    scatter.node_offset = node_offset;
    scatter.node_parent = node_parent;
    for (int m = 0; m < master_count; ++m) {
      scatter.master_unknown[m] = master_unknown[m];
      scatter.master_prescribed[m] = control.prescribed[m];
      scatter.masters[m] = masters[m];
    }
    scatter.directions = directions;
    scatter.with_residual = true;
    scatter.with_matrix = with_matrix;
    scatter.dropped = dropped_entries;
    if (with_matrix) Kokkos::deep_copy(dropped_entries, 0);
    scatter.state = state->getLocalViewDevice(Tpetra::Access::ReadOnly);
    scatter.residual = residual->getLocalViewDevice(Tpetra::Access::ReadWrite);
    if (with_matrix) {
      scatter.matrix = matrix->getLocalMatrixDevice();
      scatter.coupling = coupling->getLocalViewDevice(Tpetra::Access::ReadWrite);
    }
    return scatter;
  }

  std::array<double, master_count> master_values(const Vector& x) const
  {
    std::array<double, master_count> values{};
    for (int m = 0; m < master_count; ++m) values[m] = master_value(x, Master(m));
    return values;
  }

  double master_value(const Vector& x, Master which) const
  {
    const auto id = layout.masters[static_cast<int>(which)];
    double value = 0.0;
    const int owner = 0;
    if (comm->getRank() == owner) value = x.getData()[x.getMap()->getLocalElement(id)];
    Teuchos::broadcast(*comm, owner, Teuchos::outArg(value));
    return value;
  }

  // Residual (and tangent) of the state x: the bulk and contact blocks scattered into the global system, the
  // constraints' rows, the totals over the ranks, then the reactions.
  Evaluation evaluate(const Vector& x, Vector* out_residual, bool with_jacobian)
  {
    state->doImport(x, *importer, Tpetra::INSERT);
    const auto masters = master_values(x);
    Tpetra::beginAssembly(*residual);
    residual->putScalar(0.0);
    if (with_jacobian) {
      Tpetra::beginAssembly(*matrix, *coupling);
      matrix->setAllToScalar(0.0);
      coupling->putScalar(0.0);
    }
    DeviceView<std::int64_t[1]> inverted("inverted element");
    double energy = 0.0;
    ContactTotals contact;
    {
      const auto scatter = make_scatter(masters, with_jacobian);
      energy = assemble_bulk(scatter, with_jacobian, inverted);
      if (options.contact) contact = assemble_contact(scatter, with_jacobian);
      if (with_jacobian) add_prescribed_diagonals();
      if (with_jacobian) check_no_entry_dropped(scatter);
    }
    {
      Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: assembly communication"));
      Tpetra::endAssembly(*residual);
      if (with_jacobian) Tpetra::endAssembly(*matrix, *coupling);
    }
    auto result = totals_over_ranks(energy, contact, inverted);
    reactions_and_constraint_rows(x, result);
    if (out_residual) out_residual->assign(*residual);
    return result;
  }

  double assemble_bulk(const ElementScatter& scatter, bool with_jacobian, const DeviceView<std::int64_t[1]>& inverted)
  {
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer(
        with_jacobian ? "spatula: assembly bulk (residual + tangent)" : "spatula: assembly bulk (residual)"));
    const double energy =
        solid_model->assemble({hex8_nodes, hex13_nodes, hex8_ids, hex13_ids, coordinates}, scatter, inverted);
    Kokkos::fence();
    return energy;
  }

  ContactTotals assemble_contact(const ElementScatter& scatter, bool with_jacobian)
  {
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer(
        with_jacobian ? "spatula: assembly contact (residual + tangent)" : "spatula: assembly contact (residual)"));
    const auto contact = options.contact->assemble(contact_faces, scatter);
    Kokkos::fence();
    return contact;
  }

  // Identity rows of prescribed masters (their owner adds the diagonal once).
  void add_prescribed_diagonals()
  {
    for (int m = 0; m < master_count; ++m) {
      const int unknown = owned->getLocalElement(layout.masters[m]);
      if (!control.prescribed[m] || unknown < 0) continue;
      const detail::AddToDiagonal add{matrix->getLocalMatrixDevice(), column_of, 1.0, {-1, -1, -1}};
      Kokkos::parallel_for("spatula: prescribed master diagonal",
                           Kokkos::RangePolicy<execution_space>(unknown, unknown + 1), add);
    }
    Kokkos::fence();
  }

  static void check_no_entry_dropped(const ElementScatter& scatter)
  {
    auto dropped = Kokkos::create_mirror_view(scatter.dropped);
    Kokkos::deep_copy(dropped, scatter.dropped);
    if (dropped(0) != 0)
      throw std::logic_error(std::to_string(dropped(0)) + " tangent entries fell outside the matrix graph");
  }

  // Energies, contact face counts and the inverted-element flag summed over the ranks.
  Evaluation totals_over_ranks(double energy, const ContactTotals& contact, const DeviceView<std::int64_t[1]>& inverted)
  {
    Evaluation result;
    auto h_inverted = Kokkos::create_mirror_view(inverted);
    Kokkos::deep_copy(h_inverted, inverted);
    std::int64_t bad = h_inverted(0);
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, bad, Teuchos::outArg(bad));
    double sums[3] = {energy, contact.energy, contact.dissipated}, totals[3];
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 3, sums, totals);
    int counts[2] = {contact.active_faces, contact.skipped_faces}, count_totals[2];
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 2, counts, count_totals);
    result.internal_energy = totals[0];
    result.contact_energy = totals[1];
    result.contact_dissipated = totals[2];
    result.active_contact_faces = count_totals[0];
    result.skipped_contact_faces = count_totals[1];
    result.admissible = bad == 0;
    result.inverted_element = bad - 1;
    return result;
  }

  // Reactions: the master rows' internal forces, then prescribed rows become identity rows (residual 0) and a dead
  // load on a free master joins its row.
  void reactions_and_constraint_rows(const Vector& x, Evaluation& result)
  {
    auto values = residual->getDataNonConst(0);
    for (int m = 0; m < master_count; ++m) {
      const int unknown = owned->getLocalElement(layout.masters[m]);
      double reaction = unknown >= 0 ? values[unknown] : 0.0;
      Teuchos::broadcast(*comm, 0, Teuchos::outArg(reaction));
      result.master_residual[m] = reaction;
      if (unknown >= 0 && control.prescribed[m]) values[unknown] = 0.0;
      if (!control.prescribed[m] && control.applied[m] != 0.0) {   // a dead load on a free master
        if (unknown >= 0) values[unknown] -= control.applied[m];
        result.load_potential -= control.applied[m] * master_value(x, static_cast<Master>(m));
      }
    }
  }
};

}  // namespace spatula::discretization
