#include "solvers/algebraic_multigrid.hpp"

#include "solvers/inverse_preconditioner_factory.hpp"

#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <Tpetra_CrsGraph.hpp>

#include <algorithm>
#include <stdexcept>

namespace spatula::solvers {

using discretization::CrsMatrix;
using discretization::GlobalOrdinal;
using discretization::LocalOrdinal;
using discretization::Map;
using discretization::MultiVector;
using discretization::Node;
using discretization::execution_space;
using Hierarchy = MueLu::TpetraOperator<double, LocalOrdinal, GlobalOrdinal, Node>;

namespace {

// The MueLu parameters: those the probe of ../shared/spec/TRILINOS-NOTES.md found best for elasticity at the fine
// mesh's size, but for the coarse solve on more than one rank: MueLu's default (Amesos2 KLU2) is wrong there in
// Debian's build, and instead of the probe's repartitioning of the coarse levels onto one rank (which needs
// coordinates) relaxation is used, which the probe measured at about 3 x the iterations.
Teuchos::ParameterList multigrid_list(const Teuchos::Comm<int>& comm, Teuchos::RCP<MultiVector> modes)
{
  Teuchos::ParameterList list("MueLu");
  list.set("verbosity", "none");
  list.set("multigrid algorithm", "sa");
  list.set("number of equations", 3);
  list.set("problem: symmetric", true);
  list.set("coarse: max size", 2000);
  list.set("coarse: type", comm.getSize() > 1 ? "RELAXATION" : "KLU2");
  list.set("aggregation: type", "uncoupled");
  list.set("aggregation: drop tol", 0.02);
  list.set("sa: damping factor", 1.333);
  list.set("sa: use filtered matrix", false);
  list.set("transpose: use implicit", true);
  list.set("smoother: type", "CHEBYSHEV");
  list.sublist("smoother: params").set("chebyshev: degree", 2);
  list.sublist("smoother: params").set("chebyshev: ratio eigenvalue", 7.0);
  list.set("reuse: type", "RP");
  list.sublist("user data").set("Nullspace", modes);
  return list;
}

}  // namespace

struct AlgebraicMultigrid::State {
  std::shared_ptr<const NodeBlocks> blocks;
  int stall_applications = 0;
  MultigridStatistics statistics;
  long applications_at_init = 0;

  // The padded tangent, and where each entry of the tangent goes in it (-1: a master coupling, dropped).
  Teuchos::RCP<const Map> tangent_map;
  Teuchos::RCP<CrsMatrix> padded;
  Kokkos::View<std::int64_t*, execution_space> target_of_entry;
  Kokkos::View<LocalOrdinal*, execution_space> padded_row_of_row;   // per local row of the tangent
  Teuchos::RCP<Hierarchy> hierarchy;

  void build_pattern(const CrsMatrix& tangent);
  void copy_values(const CrsMatrix& tangent) const;
};

// The padded graph: a tangent row keeps its couplings to displacement unknowns (a master row only its diagonal);
// a padding row (a fixed component) and every master row hold only a diagonal, 1 for padding rows.
void AlgebraicMultigrid::State::build_pattern(const CrsMatrix& tangent)
{
  const auto& padded_row_of_unknown = blocks->row_of_unknown;
  const auto is_master = [this](GlobalOrdinal padded_row) {
    return padded_row >= blocks->master_block && padded_row < blocks->master_block + 3;
  };
  const auto& row_map = *tangent.getRowMap();
  const auto& column_map = *tangent.getColMap();
  const auto tangent_local = tangent.getLocalMatrixHost();
  const auto padded_rows = blocks->map->getNodeNumElements();
  std::vector<std::vector<GlobalOrdinal>> columns(padded_rows);
  for (std::size_t p = 0; p < padded_rows; ++p) columns[p].push_back(blocks->map->getGlobalElement(p));
  const auto row_count = static_cast<LocalOrdinal>(row_map.getNodeNumElements());
  padded_row_of_row = Kokkos::View<LocalOrdinal*, execution_space>("padded row of each tangent row", row_count);
  auto padded_row_host = Kokkos::create_mirror_view(padded_row_of_row);
  for (LocalOrdinal row = 0; row < row_count; ++row) {
    const auto padded_row = padded_row_of_unknown[row_map.getGlobalElement(row)];   // global
    padded_row_host(row) = blocks->map->getLocalElement(padded_row);
    if (is_master(padded_row)) continue;
    for (auto k = tangent_local.graph.row_map(row); k < tangent_local.graph.row_map(row + 1); ++k) {
      const auto padded_column = padded_row_of_unknown[column_map.getGlobalElement(tangent_local.graph.entries(k))];
      if (!is_master(padded_column) && padded_column != padded_row)
        columns[padded_row_host(row)].push_back(padded_column);
    }
  }
  Kokkos::deep_copy(padded_row_of_row, padded_row_host);
  std::size_t widest = 1;
  for (const auto& c : columns) widest = std::max(widest, c.size());
  auto graph = Teuchos::rcp(new Tpetra::CrsGraph<LocalOrdinal, GlobalOrdinal, Node>(blocks->map, widest));
  for (std::size_t p = 0; p < padded_rows; ++p)
    graph->insertGlobalIndices(blocks->map->getGlobalElement(p), Teuchos::ArrayView<const GlobalOrdinal>(columns[p]));
  graph->fillComplete();
  padded = Teuchos::rcp(new CrsMatrix(graph));
  padded->fillComplete();

  // Each tangent entry's place among the padded row's (sorted) local columns. (In a block of its own: the host view
  // of the padded matrix must be gone before its device view is taken below.)
  target_of_entry = Kokkos::View<std::int64_t*, execution_space>("padded entry of each tangent entry",
                                                                 tangent_local.values.extent(0));
  std::vector<std::int64_t> padding;   // the padding rows' diagonal entries
  {
    const auto padded_local = padded->getLocalMatrixHost();
    const auto& padded_columns = *padded->getColMap();
    auto target_host = Kokkos::create_mirror_view(target_of_entry);
    const auto entry_of = [&](LocalOrdinal padded_row, GlobalOrdinal padded_column) -> std::int64_t {
      const auto begin = padded_local.graph.entries.data() + padded_local.graph.row_map(padded_row);
      const auto end = padded_local.graph.entries.data() + padded_local.graph.row_map(padded_row + 1);
      const auto column = padded_columns.getLocalElement(padded_column);
      const auto found = std::lower_bound(begin, end, column);
      // Cannot happen (the graph was made from these entries): a logic error, not a collective failure.
      if (found == end || *found != column) throw std::logic_error("AMG: padded tangent misses an entry");
      return found - padded_local.graph.entries.data();
    };
    for (LocalOrdinal row = 0; row < row_count; ++row) {
      const auto padded_row = padded_row_of_unknown[row_map.getGlobalElement(row)];
      for (auto k = tangent_local.graph.row_map(row); k < tangent_local.graph.row_map(row + 1); ++k) {
        const auto padded_column = padded_row_of_unknown[column_map.getGlobalElement(tangent_local.graph.entries(k))];
        const bool kept = is_master(padded_row) ? padded_column == padded_row : !is_master(padded_column);
        target_host(k) = kept ? entry_of(padded_row_host(row), padded_column) : -1;
      }
    }
    Kokkos::deep_copy(target_of_entry, target_host);
    std::vector<char> has_unknown(padded_rows, 0);
    for (LocalOrdinal row = 0; row < row_count; ++row) has_unknown[padded_row_host(row)] = 1;
    for (std::size_t p = 0; p < padded_rows; ++p)
      if (!has_unknown[p]) padding.push_back(entry_of(p, blocks->map->getGlobalElement(p)));
  }
  // Padding rows get a unit diagonal, set where the values live (the device); rows with an unknown get theirs from
  // the tangent. The rigid-body modes are not zero there (zeroing them would leave aggregates of symmetry-plane
  // nodes without a Y column), so the padding rows take part in the coarse operators: a spring of stiffness 1 nN/nm
  // on each fixed component, which only the preconditioner sees.
  Kokkos::View<std::int64_t*, execution_space> padding_entries("padding diagonal entries", padding.size());
  Kokkos::deep_copy(padding_entries,
                    Kokkos::View<const std::int64_t*, Kokkos::HostSpace>(padding.data(), padding.size()));
  const auto values = padded->getLocalMatrixDevice().values;
  Kokkos::parallel_for("spatula: AMG padding diagonal",
                       Kokkos::RangePolicy<execution_space>(0, padding_entries.extent(0)),
                       KOKKOS_LAMBDA(const std::size_t k) { values(padding_entries(k)) = 1.0; });
}

void AlgebraicMultigrid::State::copy_values(const CrsMatrix& tangent) const
{
  const auto source = tangent.getLocalMatrixDevice().values;
  const auto destination = padded->getLocalMatrixDevice().values;
  const auto target = target_of_entry;
  Kokkos::parallel_for("spatula: AMG padded tangent", Kokkos::RangePolicy<execution_space>(0, source.extent(0)),
                       KOKKOS_LAMBDA(const std::size_t k) {
                         if (target(k) >= 0) destination(target(k)) = source(k);
                       });
}

namespace {

// The V-cycle on the padded rows as an operator on the tangent's rows: scatter into the padded vector (zero in the
// padding rows), apply, gather; counts its applications.
class PaddedCycle : public discretization::Operator {
public:
  explicit PaddedCycle(std::shared_ptr<AlgebraicMultigrid::State> state) : state_(std::move(state)) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return state_->tangent_map; }
  Teuchos::RCP<const Map> getRangeMap() const override { return state_->tangent_map; }
  void apply(const MultiVector& x, MultiVector& y, Teuchos::ETransp, double alpha, double beta) const override
  {
    const auto vectors = x.getNumVectors();
    if (padded_x_.is_null() || padded_x_->getNumVectors() != vectors) {
      padded_x_ = Teuchos::rcp(new MultiVector(state_->blocks->map, vectors));
      padded_y_ = Teuchos::rcp(new MultiVector(state_->blocks->map, vectors));
    }
    ++state_->statistics.applications;   // one application, whatever the number of vectors
    const auto rows = state_->padded_row_of_row;
    const auto policy = Kokkos::RangePolicy<execution_space>(0, rows.extent(0));
    {
      const auto from = x.getLocalViewDevice(Tpetra::Access::ReadOnly);
      const auto to = padded_x_->getLocalViewDevice(Tpetra::Access::OverwriteAll);
      Kokkos::deep_copy(to, 0.0);
      Kokkos::parallel_for("spatula: AMG scatter to padded rows", policy, KOKKOS_LAMBDA(const int row) {
        for (std::size_t v = 0; v < vectors; ++v) to(rows(row), v) = from(row, v);
      });
    }
    state_->hierarchy->apply(*padded_x_, *padded_y_);
    const auto from = padded_y_->getLocalViewDevice(Tpetra::Access::ReadOnly);
    const auto to = y.getLocalViewDevice(Tpetra::Access::ReadWrite);
    Kokkos::parallel_for("spatula: AMG gather from padded rows", policy, KOKKOS_LAMBDA(const int row) {
      for (std::size_t v = 0; v < vectors; ++v)
        to(row, v) = (beta == 0.0 ? 0.0 : beta * to(row, v)) + alpha * from(rows(row), v);
    });
  }

private:
  std::shared_ptr<AlgebraicMultigrid::State> state_;
  mutable Teuchos::RCP<MultiVector> padded_x_, padded_y_;
};

class MultigridPreconditionerFactory : public InversePreconditionerFactory {
public:
  MultigridPreconditionerFactory(std::shared_ptr<AlgebraicMultigrid::State> state,
                           Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>> fallback)
      : InversePreconditionerFactory("AMG"), state_(std::move(state)), fallback_(std::move(fallback))
  {
  }

  void initializePrec(const Teuchos::RCP<const Thyra::LinearOpSourceBase<double>>& source,
                      Thyra::PreconditionerBase<double>* preconditioner,
                      const Thyra::ESupportSolveUse use) const override
  {
    auto& state = *state_;
    auto& statistics = state.statistics;
    // GMRES iteration counts are global: every rank decides alike.
    if (!statistics.fell_back && statistics.setups > 0 &&
        statistics.applications - state.applications_at_init >= state.stall_applications) {
      statistics.fell_back = true;
      state.hierarchy = Teuchos::null;
      state.padded = Teuchos::null;
    }
    if (statistics.fell_back) {
      fallback_->initializePrec(source, preconditioner, use);
      return;
    }
    const auto matrix = matrix_of(*source);
    if (matrix.is_null()) throw std::logic_error("AMG preconditioner: operator is not a Tpetra CrsMatrix");
    if (state.hierarchy.is_null() || !state.tangent_map->isSameAs(*matrix->getRowMap())) {
      state.tangent_map = matrix->getRowMap();
      state.build_pattern(*matrix);
      state.copy_values(*matrix);
      auto list = multigrid_list(*state.tangent_map->getComm(), state.blocks->rigid_body_modes);
      state.hierarchy = MueLu::CreateTpetraPreconditioner(Teuchos::RCP<discretization::Operator>(state.padded), list);
      ++statistics.setups;
    } else {
      state.copy_values(*matrix);
      MueLu::ReuseTpetraPreconditioner(state.padded, *state.hierarchy);
      ++statistics.reuses;
    }
    state.applications_at_init = statistics.applications;
    hold(*preconditioner, state.tangent_map, Teuchos::rcp(new PaddedCycle(state_)));
  }

private:
  std::shared_ptr<AlgebraicMultigrid::State> state_;
  Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>> fallback_;
};

}  // namespace

AlgebraicMultigrid::AlgebraicMultigrid(std::shared_ptr<const NodeBlocks> blocks,
                                       int stall_applications)
    : state_(std::make_shared<State>())
{
  if (!blocks) throw std::invalid_argument("AMG: the unknowns' node blocks are needed");
  state_->blocks = std::move(blocks);
  state_->stall_applications = stall_applications;
}

AlgebraicMultigrid::~AlgebraicMultigrid() = default;

Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>>
AlgebraicMultigrid::preconditioner_factory(Teuchos::RCP<Thyra::PreconditionerFactoryBase<double>> fallback) const
{
  return Teuchos::rcp(new MultigridPreconditionerFactory(state_, std::move(fallback)));
}

const MultigridStatistics& AlgebraicMultigrid::statistics() const { return state_->statistics; }

}  // namespace spatula::solvers
