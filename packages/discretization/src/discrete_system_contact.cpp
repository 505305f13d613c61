// The discrete system's contact faces: their anchors, the history of a contact law with state (committed, gathered
// for checkpoints, restored from them) and the gap measures of the step control and the jumps.
#include "discretization/discrete_system_assembly.hpp"
#include "discretization/system_fields.hpp"

#include <algorithm>
#include <cmath>

namespace spatula::discretization {

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

}  // namespace spatula::discretization
