#pragma once
// The energy minimizer: from a state x at a fixed load to a stable equilibrium, where Newton alone has no
// equilibrium near (past a fold) or starts too far (a pad pressed onto a rough substrate). The total potential
// Pi = Pi_int + Pi_c is lowered by Newton steps on a shifted tangent K + eta I (eta raised until the LDL^T
// factorization shows no negative pivot, lowered again after good steps) with the line search on Pi that also
// expands the step (energy_line_search.hpp: negative curvature means going further lowers Pi more). It ends on a
// stable state confirmed by the equilibrium solver. A small gradient ends the descent only if that solver then
// converges (just past a fold the gradient is small too, with no equilibrium near); with a shift, it is first
// re-tested unshifted.
//
// Kept factors (of a positive definite shifted tangent at an earlier state) still give a descent direction -M^-1 f:
// with refactor = count they serve `reused_factors` further iterations, with refactor = cost as long as the renewal
// rule (renewal_rule.hpp) says, an iteration yielding its decrease of Pi for its seconds.
#include "solvers/equilibrium_solver.hpp"
#include "solvers/mumps_solver.hpp"
#include "solvers/spatula_model.hpp"

#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatula::solvers {

struct MinimizerParameters {
  // How a descent iteration moves: a Newton step on the tangent shifted until positive definite, with the line
  // search on Pi (each indefinite try a factorization); or a trust-region step (Steihaug-Toint truncated conjugate
  // gradients on the unshifted tangent, preconditioned by kept factors of a positive definite shifted tangent,
  // following negative curvature to the region's boundary), whose factors are renewed only when the conjugate
  // gradients stop converging (trust_region_descent.cpp); or, automatic, the trust region for systems of at least
  // `trust_region_from` unknowns (where a factorization costs many solves) and shifted Newton below.
  enum class Method { shifted_newton, trust_region, automatic };
  static const std::vector<std::string>& method_names();   // in the order of Method
  enum class Refactor { count, cost };
  static const std::vector<std::string>& refactor_names();   // in the order of Refactor

  Method method = Method::automatic;
  int trust_region_from = 100000;   // method = automatic
  int maximum_iterations = 500;
  double shift_growth = 4.0;      // eta factor while the shifted tangent is indefinite
  Refactor refactor = Refactor::count;
  int reused_factors = 0;         // refactor = count; 0: a fresh factorization every iteration
};

// Where a descent stands after an iteration: its shift eta, the mean diagonal it is measured against, and the
// iterations so far. A descent can take an hour on the paper's mesh: with its state, this is what a checkpoint
// keeps to go on from.
struct DescentProgress {
  double shift = 0.0, scale = 0.0;
  int iterations = 0;
};

struct MinimizerResult {
  bool found = false;
  int iterations = 0;        // descent iterations and the confirming solver's, when found
  std::string failure;       // why not, when not found
  bool can_go_on = false;    // not found within the iteration limit: more iterations from the last state may find it
  int indefinite_tangents = 0;   // iterations whose shifted tangent was indefinite (the shift raised)
  int accepted_steps = 0;        // iterations that lowered Pi
  // Found, an equilibrium of the contact law's descent law (discretization::DiscreteSystem::use_descent_law), not of
  // the law's own: its history is to be committed under the descent law.
  bool on_descent_law = false;
};

class EnergyMinimizer {
public:
  // `confirm`: the solver whose convergence confirms a stable state (its linear solver's MUMPS options are the
  // descent's, with exact LDL^T factors: the descent needs their inertia). `log`, `tables`: progress lines at least
  // every minute of a long descent, and the iterations' table.
  EnergyMinimizer(SpatulaModel& model, const EquilibriumSolver& confirm, std::ostream* log, bool tables);
  ~EnergyMinimizer();

  void set_parameters(const MinimizerParameters& parameters) { parameters_ = parameters; }
  // Whether a descent moves by the trust region (the method, or the automatic choice for this system's size).
  bool uses_trust_region() const;

  // Called after every descent iteration, accepted or not, with its state (collective callers welcome: every rank
  // runs the same iterations). It may throw to stop the descent.
  using Watch = std::function<void(const discretization::Vector& x, const DescentProgress& progress)>;
  // Minimizes Pi from x at the system's current load and control; x holds the last state reached, found or not.
  // `resumed`: go on with a checkpointed descent (x is its state) from its shift and iteration count.
  MinimizerResult minimize(discretization::Vector& x, const DescentProgress* resumed = nullptr,
                           const Watch& watch = {});

  // The factorizations of the descents so far (null before the first).
  const MumpsStatistics* statistics() const { return solver_ ? &solver_->statistics() : nullptr; }

private:
  struct Descent;
  struct Point;
  // The state at x (f, Pi, |f|); with `tangent` the tangent shifted by the descent's eta assembled, with `factor`
  // also factored (the negative pivots of its inertia).
  Point evaluate(const discretization::Vector& x, Descent& descent, bool tangent, bool factor,
                 discretization::Vector& f);
  std::optional<std::string> descend_to_small_gradient(discretization::Vector& x, Descent& descent,
                                                       double small_gradient, const Watch& watch);
  std::optional<std::string> descend_by_trust_region(discretization::Vector& x, Descent& descent,
                                                     double small_gradient, const Watch& watch);
  void report_progress(Descent& descent, double residual, double energy) const;
  void after_step(Descent& descent, bool fresh, double step, double decrease, double iteration_began);
  MumpsSolver& solver();

  SpatulaModel& model_;
  const EquilibriumSolver& confirm_;
  std::ostream* log_;
  bool tables_;
  MinimizerParameters parameters_;
  std::unique_ptr<MumpsSolver> solver_;   // LDL^T of the descents: one analysis for all of them
};

}  // namespace spatula::solvers
