#include "discretization/discrete_system.hpp"
#include "discretization/system_fields.hpp"
#include "discretization/system_topology.hpp"

#include "parameters/parameter_validation.hpp"
#include "discretization/solid_kernel.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Assembly_Helpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spatula::discretization {

namespace {

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

}  // namespace

// The assembly: the topology's elements and faces evaluated into the FE matrix and vectors it was built for.
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
      const AddToDiagonal add{matrix->getLocalMatrixDevice(), column_of, 1.0, {-1, -1, -1}};
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

DiscreteSystem::DiscreteSystem(const mesh::HexMesh& mesh, const mesh::Partition& partition,
                               const Constraints& constraints, const SolidParameters& solid,
                               Teuchos::RCP<const Teuchos::Comm<int>> comm, const SystemOptions& options)
    : implementation_(std::make_unique<Implementation>(mesh, partition, constraints, solid, std::move(comm), options))
{
}

DiscreteSystem::~DiscreteSystem() = default;

Teuchos::RCP<const Map> DiscreteSystem::owned_map() const { return implementation_->owned; }
Teuchos::RCP<Vector> DiscreteSystem::create_vector() const { return Teuchos::rcp(new Vector(implementation_->owned)); }
Teuchos::RCP<CrsMatrix> DiscreteSystem::jacobian() const { return implementation_->matrix; }
const DofLayout& DiscreteSystem::layout() const { return implementation_->layout; }
const NodeSpace& DiscreteSystem::nodes() const { return implementation_->space; }
const MultiVector& DiscreteSystem::load_derivatives() const { return *implementation_->coupling; }

void DiscreteSystem::set_contact_anchors(const Vector& x)
{
  auto& impl = *implementation_;
  const auto u = space_displacements(*this, x);   // collective
  DeviceView<double* [3]> anchors("contact anchors", impl.local_nodes.size());
  auto host = Kokkos::create_mirror_view(anchors);
  for (std::size_t n = 0; n < impl.local_nodes.size(); ++n)
    for (int i = 0; i < 3; ++i) {
      const auto node = impl.local_nodes[n];
      host(n, i) = impl.space.coordinates[node][i] + u[3 * node + i];
    }
  Kokkos::deep_copy(anchors, host);
  impl.contact_faces.anchors = anchors;
}

bool DiscreteSystem::commit_contact_history(const Vector& x)
{
  auto& impl = *implementation_;
  if (impl.history_per_face() == 0) return false;
  impl.evaluate(x, nullptr, false);   // the trial histories at x
  Kokkos::deep_copy(impl.committed_history, impl.contact_faces.trial_history);
  return true;
}

// Each rank writes its own faces' values into the whole array, the sum over the ranks assembles it.
std::vector<double> DiscreteSystem::contact_history() const
{
  const auto& impl = *implementation_;
  const std::size_t per_face = impl.history_per_face();
  if (per_face == 0) return {};
  const auto local = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), impl.committed_history);
  std::vector<double> mine(per_face * impl.space.faces.size(), 0.0), all(mine.size(), 0.0);
  for (std::size_t f = 0; f < impl.faces.size(); ++f)
    for (std::size_t k = 0; k < per_face; ++k) mine[impl.faces[f] * per_face + k] = local(f * per_face + k);
  Teuchos::reduceAll(*impl.comm, Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), all.data());
  return all;
}

void DiscreteSystem::set_contact_history(const std::vector<double>& all)
{
  auto& impl = *implementation_;
  const std::size_t per_face = impl.history_per_face();
  if (per_face == 0 && all.empty()) return;
  const auto* law = impl.options.contact.get();
  const std::size_t size = per_face ? law->history_size() : 0, points = size ? per_face / size : 0;
  const std::size_t given = size ? law->stored_history_width(all.size(), points * impl.space.faces.size()) : 0;
  if (given == 0)
    throw std::runtime_error("a contact history of " + std::to_string(all.size()) + " values given, the system's has " +
                             std::to_string(per_face * impl.space.faces.size()));
  auto local = Kokkos::create_mirror_view(impl.committed_history);
  for (std::size_t f = 0; f < impl.faces.size(); ++f)
    for (std::size_t p = 0; p < points; ++p)
      for (std::size_t k = 0; k < size; ++k)
        local(f * per_face + p * size + k) = k < given ? all[(impl.faces[f] * points + p) * given + k] : 0.0;
  Kokkos::deep_copy(impl.committed_history, local);
}

GapChanges DiscreteSystem::contact_gap_changes(const Vector& from, const Vector& to, double fraction)
{
  auto& impl = *implementation_;
  GapChanges changes;
  if (!impl.options.contact) return changes;
  if (!impl.other_state) impl.other_state = Teuchos::rcp(new Vector(impl.overlap));
  impl.state->doImport(from, *impl.importer, Tpetra::INSERT);
  impl.other_state->doImport(to, *impl.importer, Tpetra::INSERT);
  const auto scatter_from = impl.make_scatter(impl.master_values(from), false);
  auto scatter_to = scatter_from;
  scatter_to.state = impl.other_state->getLocalViewDevice(Tpetra::Access::ReadOnly);
  const auto masters_to = impl.master_values(to);
  for (int m = 0; m < master_count; ++m) scatter_to.masters[m] = masters_to[m];
  const auto local = impl.options.contact->gap_changes(impl.contact_faces, scatter_from, scatter_to, fraction);
  std::array<double, gap_change_sums> sums{};
  Teuchos::reduceAll(*impl.comm, Teuchos::REDUCE_SUM, gap_change_sums, local.data(), sums.data());
  changes.crossing = static_cast<int>(sums[0]);
  changes.large = static_cast<int>(sums[1]);
  if (changes.crossing > 0)
    for (int i = 0; i < 2; ++i) {
      changes.mean[i] = sums[2 + i] / sums[0];
      changes.spread[i] = std::sqrt(std::max(0.0, sums[4 + i] / sums[0] - changes.mean[i] * changes.mean[i]));
    }
  for (int k = 0; k < 4; ++k) changes.energy_change[k] = sums[6 + k];
  changes.adhering_area = sums[10];
  if (sums[10] > 0.0) changes.mean_slip = sums[11] / sums[10];
  return changes;
}

GapLimit DiscreteSystem::contact_gap_limit(const Vector& from, const Vector& to, double beyond, Vector& row)
{
  auto& impl = *implementation_;
  GapLimit limit;
  row.putScalar(0.0);
  if (!impl.options.contact) return limit;
  if (!impl.other_state) impl.other_state = Teuchos::rcp(new Vector(impl.overlap));
  impl.state->doImport(from, *impl.importer, Tpetra::INSERT);
  impl.other_state->doImport(to, *impl.importer, Tpetra::INSERT);
  Tpetra::beginAssembly(*impl.residual);   // (the residual's storage, until the next evaluation)
  impl.residual->putScalar(0.0);
  std::array<double, gap_limit_sums> local{};
  {
    const auto scatter_from = impl.make_scatter(impl.master_values(from), false);
    auto scatter_to = scatter_from;
    scatter_to.state = impl.other_state->getLocalViewDevice(Tpetra::Access::ReadOnly);
    const auto masters_to = impl.master_values(to);
    for (int m = 0; m < master_count; ++m) scatter_to.masters[m] = masters_to[m];
    local = impl.options.contact->gap_limit(impl.contact_faces, scatter_from, scatter_to, beyond);
    Kokkos::fence();
  }
  Tpetra::endAssembly(*impl.residual);
  row.assign(*impl.residual);
  for (int m = 0; m < master_count; ++m)
    if (impl.control.prescribed[m]) set_master(row, Master(m), 0.0);
  std::array<double, gap_limit_sums> sums{};
  Teuchos::reduceAll(*impl.comm, Teuchos::REDUCE_SUM, gap_limit_sums, local.data(), sums.data());
  limit.points = static_cast<int>(sums[0]);
  limit.target = sums[1];
  return limit;
}

double DiscreteSystem::mean_diagonal() const
{
  const auto& matrix = *implementation_->matrix;
  Vector diagonal(matrix.getRowMap());
  matrix.getLocalDiagCopy(diagonal);
  return diagonal.norm1() / static_cast<double>(diagonal.getGlobalLength());
}
double DiscreteSystem::contact_area() const { return implementation_->half_contact_area; }
void DiscreteSystem::set_control(const MasterControl& control) { implementation_->control = control; }
const MasterControl& DiscreteSystem::control() const { return implementation_->control; }

double DiscreteSystem::master(const Vector& x, Master which) const { return implementation_->master_value(x, which); }

void DiscreteSystem::set_master(Vector& x, Master which, double value) const
{
  const auto id = implementation_->layout.masters[static_cast<int>(which)];
  if (x.getMap()->isNodeGlobalElement(id)) x.replaceGlobalValue(id, value);
}

Evaluation DiscreteSystem::evaluate(const Vector& x, Vector* residual, bool with_jacobian)
{
  return implementation_->evaluate(x, residual, with_jacobian);
}

const SystemTopology& DiscreteSystem::topology() const { return *implementation_; }
const SolidParameters& DiscreteSystem::solid() const { return implementation_->solid; }
const SolidModel& DiscreteSystem::solid_model() const { return *implementation_->solid_model; }
const ContactModel* DiscreteSystem::contact_model() const { return implementation_->options.contact.get(); }

bool DiscreteSystem::has_descent_law() const { return implementation_->descent_law != nullptr; }

void DiscreteSystem::use_descent_law(bool on)
{
  auto& impl = *implementation_;
  if (!impl.law) return;
  impl.options.contact = on && impl.descent_law ? impl.descent_law : impl.law;
}

}  // namespace spatula::discretization
