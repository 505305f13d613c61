#pragma once
// MUMPS as a distributed direct solver for Tpetra matrices, usable as a Tpetra::Operator that applies A^-1.
//
// Each rank hands MUMPS its owned rows (distributed assembled input, ICNTL(18) = 3); the right-hand side and the
// solution travel through rank 0 (centralized dense RHS). The symbolic analysis is done once for a sparsity
// pattern and reused by every later numerical factorization. Symmetric mode uses LDL^T with pivoting (SYM = 2),
// which handles the indefinite tangents met near instabilities, and reports the number of negative pivots (the
// inertia: how many eigenvalues of the tangent are negative).
#include "discretization/tpetra_types.hpp"

#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace spatula::solvers {

using discretization::CrsMatrix;
using discretization::Map;
using discretization::MultiVector;
using discretization::Operator;

// A factorization refused because of the matrix itself (numerically singular, non-finite entries): the one failure a
// caller may answer by changing the matrix (a shift). Any other failure (solvers::OutOfMemory, MUMPS' own errors) is not.
class UnusableMatrix : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Fill-reducing orderings MUMPS may offer (ICNTL(7)); which are built in depends on the MUMPS library linked.
enum class MumpsOrdering { automatic, amd, amf, qamd, pord, scotch, metis };
const std::vector<std::string>& mumps_ordering_names();   // in the order of MumpsOrdering

struct MumpsParameters {
  bool symmetric = true;        // LDL^T (SYM = 2); false: LU (SYM = 0)
  int memory_relaxation = 40;   // ICNTL(14), per cent
  bool verbose = false;         // MUMPS' own statistics on standard output
  bool keep_workspace = true;   // freed memory stays in the process for the next factorization (mallopt)
  MumpsOrdering ordering = MumpsOrdering::automatic;
  double low_rank_tolerance = 1e-5;   // block low-rank factorization (ICNTL(35), CNTL(7)); 0: full rank
  int low_rank_from = 100000;          // ... for systems of at least this many unknowns (smaller: full rank)
  bool single_precision = false;       // factors in single precision (SMUMPS): a GMRES preconditioner, not exact
  // These options with exact factors: LDL^T, full rank, double precision (for users of the factors' inertia).
  MumpsParameters exact_ldlt() const;
  // The keys with their defaults (`defaults`: those of the solver that declares them, e.g. the Newton tangents').
  static void declare(Teuchos::ParameterList& list, const MumpsParameters& defaults);
  static MumpsParameters from(const Teuchos::ParameterList& list);
};

struct MumpsStatistics {
  int analyses = 0;
  int factorizations = 0;
  int solves = 0;
  int negative_pivots = -1;   // from the last factorization (symmetric mode), -1 if unknown
  int workspace_increases = 0;   // factorizations repeated with a larger ICNTL(14)
  int null_pivots = 0;          // of the last factorization (ICNTL(24) null pivot detection)
  int applications_since_factor = 0;   // solves done with the current factors (lagging decisions)
  int reused = 0;               // times a stale factorization was kept as preconditioner
  double analysis_seconds = 0.0, factorization_seconds = 0.0, solve_seconds = 0.0;
  double last_factorization_seconds = 0.0;   // wall time of the latest factorization
  std::string ordering_used;      // INFOG(7) of the latest analysis
  double factorization_flops = 0.0;   // RINFOG(3): operations of the latest factorization
  double factor_entries = 0.0;        // INFOG(29) (INFOG(9) without low rank): entries in the factors
  int factorization_megabytes = 0;    // INFOG(22): memory of the factorization summed over the ranks
};

class MumpsSolver : public Operator {
public:
  MumpsSolver(Teuchos::RCP<const Map> map, const MumpsParameters& parameters);
  ~MumpsSolver() override;

  // Numerical factorization of A (its row map must be the solver's map); analysis on first use or when the
  // number of stored entries changes. Throws std::runtime_error naming the MUMPS error (e.g. a singular matrix).
  void factor(const CrsMatrix& matrix);

  // Y = alpha A^-1 X + beta Y (mode must be NO_TRANS; the factorized matrix is symmetric anyway).
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1.0, double beta = 0.0) const override;
  Teuchos::RCP<const Map> getDomainMap() const override;
  Teuchos::RCP<const Map> getRangeMap() const override;

  const MumpsStatistics& statistics() const;
  void count_reuse();   // a stale factorization kept as preconditioner (see LinearSolverParameters::lag)

  struct Implementation;   // the factors of one precision (mumps_solver.cpp)

private:
  std::unique_ptr<Implementation> implementation_;
};

}  // namespace spatula::solvers
