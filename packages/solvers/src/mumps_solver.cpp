#include "solvers/mumps_solver.hpp"

#include "parameters/parameter_validation.hpp"
#include "solvers/out_of_memory.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Import.hpp>

#include <dmumps_c.h>
#include <smumps_c.h>
#include <malloc.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace spatula::solvers {

using discretization::GlobalOrdinal;
using discretization::Import;

const std::vector<std::string>& mumps_ordering_names()
{
  static const std::vector<std::string> names = {"automatic", "AMD", "AMF", "QAMD", "PORD", "SCOTCH", "METIS"};
  return names;
}

namespace {

// ICNTL(7) of each MumpsOrdering, in the same order.
constexpr int ordering_codes[] = {7, 0, 2, 6, 4, 3, 5};

std::string ordering_name(int code)
{
  for (std::size_t i = 0; i < std::size(ordering_codes); ++i)
    if (ordering_codes[i] == code) return mumps_ordering_names()[i];
  return "ICNTL(7) = " + std::to_string(code);
}

}  // namespace

void MumpsParameters::declare(Teuchos::ParameterList& list, const MumpsParameters& d)
{
  parameters::declare_bool(list, "symmetric", d.symmetric,
                           "LDL^T factorization (symmetric indefinite); false: LU");
  parameters::declare_int(list, "memory relaxation", d.memory_relaxation, "MUMPS ICNTL(14): extra workspace [%]",
                          parameters::Range::closed(0, 1000));
  parameters::declare_bool(list, "verbose", d.verbose, "print MUMPS' statistics of every analysis and factorization");
  parameters::declare_bool(list, "keep workspace", d.keep_workspace,
                           "keep memory MUMPS frees in the process for its next factorization (glibc: large blocks "
                           "not mapped, free memory not trimmed); false: glibc's defaults, which map and unmap the "
                           "factor workspace at every factorization");
  parameters::declare_string(list, "ordering", parameters::name_of(d.ordering, mumps_ordering_names()),
                             "fill-reducing ordering (ICNTL(7)); SCOTCH and METIS need a MUMPS built with them, "
                             "otherwise the analysis refuses the run; automatic: MUMPS' choice",
                             mumps_ordering_names());
  // Measured on the fine mesh (318,087 unknowns, 2 ranks, benchmarks/solid_benchmark): 1e-5 makes a Newton iteration
  // 0.80 x as long and the factors 0.75 x as large; on the medium mesh a factorization is too small to gain.
  parameters::declare_double(list, "low rank tolerance", d.low_rank_tolerance,
                             "block low-rank factorization with this dropping threshold (ICNTL(35) = 2, CNTL(7)) for "
                             "systems of at least 'low rank from' unknowns; the factors are then approximate and serve "
                             "as a GMRES preconditioner (the Newton directions stay exact); 0: full rank always",
                             parameters::Range::closed(0.0, 0.1));
  parameters::declare_int(list, "low rank from", d.low_rank_from,
                          "unknowns from which the low-rank factorization is used (smaller systems: full rank)",
                          parameters::Range::closed(0, std::numeric_limits<int>::max()));
  parameters::declare_string(list, "factor precision", d.single_precision ? "single" : "double",
                             "single: the factors in single precision (MUMPS' SMUMPS: half the memory and the memory "
                             "traffic of the solves), a GMRES preconditioner of the double-precision tangent (the Newton "
                             "directions stay exact); the energy descents of jumps and the tangent spectrum keep "
                             "double-precision factors, whose inertia they need", {"double", "single"});
}

MumpsParameters MumpsParameters::exact_ldlt() const
{
  MumpsParameters exact = *this;
  exact.symmetric = true;
  exact.low_rank_tolerance = 0.0;
  exact.single_precision = false;
  return exact;
}

MumpsParameters MumpsParameters::from(const Teuchos::ParameterList& list)
{
  MumpsParameters p;
  p.symmetric = list.get<bool>("symmetric");
  p.memory_relaxation = list.get<int>("memory relaxation");
  p.verbose = list.get<bool>("verbose");
  p.keep_workspace = list.get<bool>("keep workspace");
  p.ordering = parameters::choice<MumpsOrdering>(list, "ordering", mumps_ordering_names());
  p.low_rank_tolerance = list.get<double>("low rank tolerance");
  p.low_rank_from = list.get<int>("low rank from");
  p.single_precision = list.get<std::string>("factor precision") == "single";
  return p;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The two MUMPS instances used: double precision (DMUMPS) and single precision (SMUMPS) factors.
void call(DMUMPS_STRUC_C& id) { dmumps_c(&id); }
void call(SMUMPS_STRUC_C& id) { smumps_c(&id); }

// ICNTL/INFOG are 1-based in the MUMPS documentation.
template <class Id> int& icntl(Id& id, int index) { return id.icntl[index - 1]; }
template <class Id> int infog(const Id& id, int index) { return id.infog[index - 1]; }
template <class Id> double rinfog(const Id& id, int index) { return id.rinfog[index - 1]; }

template <class Id> std::string describe_error(const Id& id)
{
  const int code = infog(id, 1), detail = infog(id, 2);
  std::string what = "MUMPS error INFOG(1) = " + std::to_string(code) + ", INFOG(2) = " + std::to_string(detail);
  if (code == -9 || code == -8) what += " (MUMPS' workspace estimate too small; raise 'memory relaxation')";
  return what;
}

// Throws for a failed phase (INFOG(1) < 0), the same on every rank (MUMPS reports each rank's error to all):
// OutOfMemory where the system refused MUMPS an allocation (-13: INFOG(2) scalars, negative in millions; -7: the
// analysis' integers),
// UnusableMatrix where the matrix is the cause (-10, numerically singular), a runtime_error otherwise.
template <class Id> void check(const Id& id, const char* phase)
{
  const int code = infog(id, 1);
  if (code >= 0) return;
  if (code == -13 || code == -7) {   // -7: the analysis' integer workspace (INFOG(2) integers)
    const double items = infog(id, 2) < 0 ? -1e6 * infog(id, 2) : double(infog(id, 2));
    const double item_bytes = code == -7 ? sizeof(int) : sizeof(*id.a_loc);
    throw OutOfMemory(std::string("MUMPS ") + phase + " workspace (" + describe_error(id) + ")", item_bytes * items,
                      true);
  }
  const std::string what = std::string("MUMPS ") + phase + " failed: " + describe_error(id);
  if (code == -10) throw UnusableMatrix(what + " (numerically singular matrix)");
  throw std::runtime_error(what);
}

// MUMPS allocates its factor workspace (about 280 MB on the medium mesh) at every factorization and frees it after.
// With glibc's defaults a block that large is mmap-ed and munmap-ed each time, and every page of it faults in again:
// measured on the medium mesh, 1.08 M page faults and 7 s of system time in 20 factorizations, half of the
// factorization's time (../shared/peers/README.md). Large blocks from the heap, and a heap that is never trimmed,
// let every factorization after the first reuse the pages of the one before. Process-wide, set once.
void keep_freed_memory()
{
  static const bool done = [] {
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
    return true;
  }();
  (void)done;
}

}  // namespace

// What the solver does whatever the precision of its factors.
struct MumpsSolver::Implementation {
  virtual ~Implementation() = default;
  virtual void factor(const CrsMatrix& matrix) = 0;
  virtual void solve(const MultiVector& X, MultiVector& Y, double alpha, double beta) const = 0;
  Teuchos::RCP<const Map> map;
  MumpsParameters parameters;
  mutable MumpsStatistics statistics;
};

namespace {

// The factors of one MUMPS instance: Id = DMUMPS_STRUC_C (double) or SMUMPS_STRUC_C (single; the matrix and the
// right-hand sides are rounded to float on their way in, the solutions widened on their way out).
template <class Id>
struct Factors final : MumpsSolver::Implementation {
  using Real = std::remove_pointer_t<decltype(Id::a_loc)>;
  Teuchos::RCP<const Map> root_map;   // every unknown on rank 0
  Teuchos::RCP<const Import> to_root;
  Id id{};
  bool analysed = false;
  std::vector<int> rows, columns;   // 1-based global indices of the entries handed to MUMPS
  std::vector<Real> values;
  std::size_t analysed_entries = 0;   // stored entries of the matrix the analysis was done for
  mutable std::vector<Real> right_hand_side;

  Factors(Teuchos::RCP<const Map> map_, const MumpsParameters& parameters_)
  {
    map = std::move(map_);
    parameters = parameters_;
    const auto comm = map->getComm();
    const auto mpi_comm = Teuchos::rcp_dynamic_cast<const Teuchos::MpiComm<int>>(comm);
    if (mpi_comm.is_null()) throw std::logic_error("MumpsSolver needs an MPI communicator");
    const GlobalOrdinal count = static_cast<GlobalOrdinal>(map->getGlobalNumElements());
    if (map->getMinAllGlobalIndex() != 0 || map->getMaxAllGlobalIndex() != count - 1)
      throw std::logic_error("MumpsSolver needs global ids 0..n-1");
    std::vector<GlobalOrdinal> all;
    if (comm->getRank() == 0)
      for (GlobalOrdinal i = 0; i < count; ++i) all.push_back(i);
    root_map = Teuchos::rcp(new Map(count, all.data(), all.size(), 0, comm));
    to_root = Teuchos::rcp(new Import(map, root_map));

    if (parameters.keep_workspace) keep_freed_memory();
    id.comm_fortran = static_cast<int>(MPI_Comm_c2f(*mpi_comm->getRawMpiComm()));
    id.par = 1;   // rank 0 works too
    id.sym = parameters.symmetric ? 2 : 0;
    id.job = -1;
    call(id);
    icntl(id, 1) = -1;   // no MUMPS printing: errors are reported through exceptions
    icntl(id, 2) = -1;
    icntl(id, 3) = -1;
    icntl(id, 4) = 0;
    if (parameters.verbose) {   // MUMPS' own statistics on standard output (diagnosis of a hard factorization)
      icntl(id, 1) = icntl(id, 2) = icntl(id, 3) = 6;
      icntl(id, 4) = 2;
    }
    icntl(id, 5) = 0;    // assembled matrix
    icntl(id, 18) = 3;   // distributed entries
    icntl(id, 14) = parameters.memory_relaxation;
    icntl(id, 20) = 0;   // dense centralized right-hand side
    icntl(id, 21) = 0;   // centralized solution
    icntl(id, 24) = 1;   // null pivot detection: an exactly singular tangent (at a fold) still gives a direction
    icntl(id, 7) = ordering_codes[static_cast<int>(parameters.ordering)];
    icntl(id, 28) = 1;   // sequential analysis, so that ICNTL(7) is the ordering used
    if (map->getGlobalNumElements() < static_cast<std::size_t>(parameters.low_rank_from))
      parameters.low_rank_tolerance = 0.0;   // small: full rank (the approximate factors would not pay)
    if (parameters.low_rank_tolerance > 0.0) {
      icntl(id, 35) = 2;   // block low-rank factorization (and full-rank solve of the compressed factors)
      id.cntl[7 - 1] = parameters.low_rank_tolerance;
    }
  }

  ~Factors() override
  {
    id.job = -2;
    call(id);
  }

  void collect(const CrsMatrix& matrix, bool pattern)
  {
    const auto row_map = matrix.getRowMap();
    const auto column_map = matrix.getColMap();
    if (pattern) {
      rows.clear();
      columns.clear();
    }
    values.clear();
    for (std::size_t lid = 0; lid < row_map->getNodeNumElements(); ++lid) {
      typename CrsMatrix::local_inds_host_view_type indices;
      typename CrsMatrix::values_host_view_type entries;
      matrix.getLocalRowView(static_cast<int>(lid), indices, entries);
      const auto row = row_map->getGlobalElement(lid);
      for (std::size_t k = 0; k < indices.extent(0); ++k) {
        const auto column = column_map->getGlobalElement(indices(k));
        if (parameters.symmetric && column > row) continue;   // one triangle only (MUMPS sums duplicates)
        if (pattern) {
          rows.push_back(static_cast<int>(row + 1));
          columns.push_back(static_cast<int>(column + 1));
        }
        values.push_back(static_cast<Real>(entries(k)));
      }
    }
  }

  void factor(const CrsMatrix& matrix) override
  {
    if (!matrix.getRowMap()->isSameAs(*map)) throw std::logic_error("MumpsSolver: matrix row map differs");
    // The decision must be the same on every rank (MUMPS calls are collective).
    int changed = !analysed || matrix.getNodeNumEntries() != analysed_entries;
    Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_MAX, changed, Teuchos::outArg(changed));
    const bool pattern = changed != 0;
    collect(matrix, pattern);
    int finite = std::all_of(values.begin(), values.end(), [](Real v) { return std::isfinite(v); });
    Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_MIN, finite, Teuchos::outArg(finite));
    if (!finite) throw UnusableMatrix("MUMPS factorization refused: the tangent has non-finite entries");
    id.n = static_cast<int>(map->getGlobalNumElements());
    id.nnz_loc = static_cast<MUMPS_INT8>(rows.size());
    id.irn_loc = rows.data();
    id.jcn_loc = columns.data();
    id.a_loc = values.data();
    if (pattern) {
      Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: linear solve (MUMPS analysis)"));
      const auto start = std::chrono::steady_clock::now();
      id.job = 1;
      call(id);
      check(id, "analysis");
      statistics.ordering_used = ordering_name(infog(id, 7));
      const MumpsOrdering asked = parameters.ordering;
      if (asked != MumpsOrdering::automatic && infog(id, 7) != ordering_codes[static_cast<int>(asked)])
        throw std::runtime_error("'Linear Solver/MUMPS/ordering' = " + parameters::name_of(asked, mumps_ordering_names()) +
                                 " is not built into the MUMPS library this program uses (it ordered with " +
                                 statistics.ordering_used + "); choose another ordering or automatic");
      analysed = true;
      analysed_entries = matrix.getNodeNumEntries();
      ++statistics.analyses;
      statistics.analysis_seconds += seconds_since(start);
    }
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: linear solve (MUMPS factorization)"));
    const auto start = std::chrono::steady_clock::now();
    // Pivoting on indefinite matrices can need more workspace than the analysis estimated: retry with more.
    for (int attempt = 0;; ++attempt) {
      id.job = 2;
      call(id);
      const int code = infog(id, 1);
      const bool workspace = code == -8 || code == -9 || code == -14 || code == -15 || code == -17 || code == -20;
      if (!workspace || attempt == 4) break;
      icntl(id, 14) = 2 * std::max(icntl(id, 14), 20);
      ++statistics.workspace_increases;
    }
    check(id, "factorization");
    ++statistics.factorizations;
    statistics.applications_since_factor = 0;
    statistics.last_factorization_seconds = seconds_since(start);
    statistics.factorization_seconds += statistics.last_factorization_seconds;
    statistics.factorization_flops = rinfog(id, 3);
    statistics.factor_entries = parameters.low_rank_tolerance > 0.0 ? infog(id, 29) : infog(id, 9);
    if (statistics.factor_entries < 0) statistics.factor_entries *= -1e6;   // MUMPS: negative = millions
    statistics.factorization_megabytes = infog(id, 22);
    statistics.negative_pivots = parameters.symmetric ? infog(id, 12) : -1;
    statistics.null_pivots = infog(id, 28);
  }

  void solve(const MultiVector& X, MultiVector& Y, double alpha, double beta) const override
  {
    Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: linear solve (MUMPS solve)"));
    const auto start = std::chrono::steady_clock::now();
    const std::size_t vectors = X.getNumVectors();
    MultiVector root(root_map, vectors);
    root.doImport(X, *to_root, Tpetra::INSERT);
    const int n = static_cast<int>(map->getGlobalNumElements());
    const bool is_root = map->getComm()->getRank() == 0;
    if (is_root) {
      right_hand_side.resize(static_cast<std::size_t>(n) * vectors);
      for (std::size_t v = 0; v < vectors; ++v) {
        const auto data = root.getData(v);
        std::copy(data.begin(), data.end(), right_hand_side.begin() + v * n);
      }
    }
    auto& mutable_id = const_cast<Id&>(id);
    mutable_id.nrhs = static_cast<int>(vectors);
    mutable_id.lrhs = n;
    mutable_id.rhs = is_root ? right_hand_side.data() : nullptr;
    mutable_id.job = 3;
    call(mutable_id);
    check(id, "solve");
    if (is_root)
      for (std::size_t v = 0; v < vectors; ++v) {
        auto data = root.getDataNonConst(v);
        std::copy(right_hand_side.begin() + v * n, right_hand_side.begin() + (v + 1) * n, data.begin());
      }
    MultiVector solution(map, vectors);
    solution.doExport(root, *to_root, Tpetra::INSERT);
    Y.update(alpha, solution, beta);
    ++statistics.solves;
    ++statistics.applications_since_factor;
    statistics.solve_seconds += seconds_since(start);
  }
};

std::unique_ptr<MumpsSolver::Implementation> make_factors(Teuchos::RCP<const Map> map,
                                                          const MumpsParameters& parameters)
{
  if (parameters.single_precision) return std::make_unique<Factors<SMUMPS_STRUC_C>>(std::move(map), parameters);
  return std::make_unique<Factors<DMUMPS_STRUC_C>>(std::move(map), parameters);
}

}  // namespace

MumpsSolver::MumpsSolver(Teuchos::RCP<const Map> map, const MumpsParameters& parameters)
    : implementation_(make_factors(std::move(map), parameters))
{
}

MumpsSolver::~MumpsSolver() = default;

void MumpsSolver::factor(const CrsMatrix& matrix) { implementation_->factor(matrix); }

void MumpsSolver::apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, double alpha, double beta) const
{
  if (mode != Teuchos::NO_TRANS && !implementation_->parameters.symmetric)
    throw std::logic_error("MumpsSolver: transposed solves are not supported in LU mode");
  implementation_->solve(X, Y, alpha, beta);
}

Teuchos::RCP<const Map> MumpsSolver::getDomainMap() const { return implementation_->map; }
Teuchos::RCP<const Map> MumpsSolver::getRangeMap() const { return implementation_->map; }
const MumpsStatistics& MumpsSolver::statistics() const { return implementation_->statistics; }
void MumpsSolver::count_reuse() { ++implementation_->statistics.reused; }

}  // namespace spatula::solvers
