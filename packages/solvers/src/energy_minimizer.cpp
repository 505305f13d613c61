#include "solvers/energy_minimizer.hpp"
#include "solvers/descent_state.hpp"
#include "solvers/energy_line_search.hpp"
#include "solvers/renewal_rule.hpp"
#include "solvers/tangent_shift.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace spatula::solvers {

const std::vector<std::string>& MinimizerParameters::method_names()
{
  static const std::vector<std::string> names = {"shifted newton", "trust region", "auto"};
  return names;
}

const std::vector<std::string>& MinimizerParameters::refactor_names()
{
  static const std::vector<std::string> names = {"count", "cost"};
  return names;
}

EnergyMinimizer::EnergyMinimizer(SpatulaModel& model, const EquilibriumSolver& confirm, std::ostream* log,
                                 bool tables)
    : model_(model), confirm_(confirm), log_(log), tables_(tables)
{
}

EnergyMinimizer::~EnergyMinimizer() = default;

bool EnergyMinimizer::uses_trust_region() const
{
  using Method = MinimizerParameters::Method;
  if (parameters_.method != Method::automatic) return parameters_.method == Method::trust_region;
  return model_.system().owned_map()->getGlobalNumElements() >=
         static_cast<std::size_t>(parameters_.trust_region_from);
}

MumpsSolver& EnergyMinimizer::solver()
{
  if (!solver_)   // the user's MUMPS options, but exact LDL^T factors: the descent needs their inertia
    solver_ = std::make_unique<MumpsSolver>(model_.system().owned_map(),
                                            confirm_.linear_solver().parameters().mumps.exact_ldlt());
  return *solver_;
}

EnergyMinimizer::Point EnergyMinimizer::evaluate(const discretization::Vector& x, Descent& d, bool tangent,
                                                 bool factor, discretization::Vector& f)
{
  auto& system = model_.system();
  const auto evaluation = system.evaluate(x, &f, tangent);
  if (tangent && d.eta > 0.0 && evaluation.admissible) shift_tangent(system, d.eta);   // anchored at x: f unchanged
  Point point{evaluation.admissible, evaluation.energy(), f.norm2(), 0};
  if (!point.admissible) return point;
  if (d.scale == 0.0) d.scale = system.mean_diagonal();
  if (factor) {
    try {
      solver().factor(*system.jacobian());
      point.negative_pivots = solver().statistics().negative_pivots;
    } catch (const UnusableMatrix&) {
      point.negative_pivots = 1;   // singular: treat like indefinite (any other failure is not the matrix's: it ends the run)
    }
  }
  return point;
}

void EnergyMinimizer::after_step(Descent& d, bool fresh, double step, double decrease, double iteration_began)
{
  using Refactor = MinimizerParameters::Refactor;
  if (parameters_.refactor == Refactor::cost && fresh) {   // a new cycle: one kept iteration at least
    d.cost.factored(now() - d.cycle_began, decrease);
    d.kept = 1;
  } else if (parameters_.refactor == Refactor::cost) {
    // The clocks differ by rank: any rank that would refactor decides for all.
    int keep = d.cost.keep(now() - iteration_began, decrease) ? 1 : 0;
    Teuchos::reduceAll(*model_.system().owned_map()->getComm(), Teuchos::REDUCE_MIN, keep, Teuchos::outArg(keep));
    if (keep) d.kept = 1;
    else d.refactor();
  } else if (fresh) {
    d.kept = parameters_.reused_factors;
  } else {
    --d.kept;
  }
  if (fresh) {
    d.eta = step >= 1.0 ? 0.25 * d.eta : 2.0 * d.eta;
    if (d.eta < 1e-9 * d.scale) d.eta = 0.0;
  }
  // refactor = count: a short step means the factors no longer fit the energy's curvature here
  if (parameters_.refactor == Refactor::count && step < 0.5) d.kept = 0;
}

std::optional<std::string> EnergyMinimizer::descend_to_small_gradient(discretization::Vector& x, Descent& d,
                                                                      double small_gradient, const Watch& watch)
{
  auto& system = model_.system();
  auto f = system.create_vector(), direction = system.create_vector(), trial = system.create_vector();
  d.cycle_began = now();   // a cycle is not charged with the confirming solve between two calls
  // After every iteration, accepted or not (an indefinite try costs a factorization: a minute on the paper's mesh),
  // the descent is offered to the watch (checkpoint, signal).
  for (; d.iteration < parameters_.maximum_iterations; watch ? watch(x, d.progress()) : void(), ++d.iteration) {
    const double iteration_began = now();
    // Kept factors still give a descent direction -M^-1 f; the iteration then needs only f and Pi. Otherwise the
    // tangent at x is assembled and factored.
    const bool fresh = d.kept == 0;
    const auto point = evaluate(x, d, fresh, fresh, *f);
    if (!point.admissible) return std::string("an element inverted during the energy descent");
    if (point.negative_pivots > 0) {   // not a descent direction yet: shift more
      d.row(tables_, point.negative_pivots, point.residual, 0.0, point.energy);
      ++d.indefinite;
      if (auto stop = d.stiffen(parameters_.shift_growth)) return stop;
      continue;
    }
    // Near a stable minimum (positive definite tangent, small gradient): the equilibrium solver finishes. The energy
    // alone cannot resolve the last digits (its changes fall below its rounding), the gradient can. A small gradient
    // found with a shift is tested once without it: is the unshifted tangent positive definite there? (Without this
    // a descent that has reached the minimum keeps raising the shift, since no step can lower Pi any more.)
    d.residual = point.residual;
    report_progress(d, point.residual, point.energy);
    if (point.residual < small_gradient && (d.eta == 0.0 || !d.unshifted_tried || !fresh)) {
      d.row(tables_, fresh ? point.negative_pivots : -1, point.residual, 0.0, point.energy);
      if (!fresh) {   // the tests below need the inertia at this state
        d.refactor();
        continue;
      }
      if (d.eta == 0.0) return std::nullopt;
      d.unshifted_tried = true;
      d.eta = 0.0;
      continue;
    }
    solver().apply(*f, *direction);
    if (!fresh) solver().count_reuse();   // an iteration served by kept factors
    direction->scale(-1.0);
    const double slope = f->dot(*direction);
    const auto best = search_energy_decrease(
        [&](double step) {
          trial->update(1.0, x, step, *direction, 0.0);
          const auto evaluation = system.evaluate(*trial, nullptr, false);
          return LinePoint{step, 0.0, evaluation.energy(), evaluation.admissible};
        },
        LinePoint{0.0, slope, point.energy, true});
    d.row(tables_, fresh ? point.negative_pivots : -1, point.residual, best.step, best.energy);
    if (best.step == 0.0 && !fresh) {   // the kept factors are out of date: fresh ones at this state
      d.cost.keep(now() - iteration_began, 0.0);   // (their cycle's last, fruitless iteration)
      d.refactor();
      continue;
    }
    // A descent direction along which Pi does not measurably decrease: rounding; let the solver finish. But a
    // direction that is not one (slope >= 0: the factors of a nearly singular tangent whose inertia showed no
    // negative pivot lost it to rounding) is shifted like an indefinite tangent.
    if (best.step == 0.0 && d.eta == 0.0 && slope < 0.0) return std::nullopt;
    if (best.step == 0.0 && slope >= 0.0 && tables_)
      d.table << "  descent  (not a descent direction: slope " << slope << " nN nm; shifting the tangent)\n";
    if (best.step == 0.0) {   // no decrease along this direction: stiffen the shift
      ++d.no_decrease;
      if (auto stop = d.stiffen(parameters_.shift_growth)) return stop;
      continue;
    }
    ++d.accepted;
    d.unshifted_tried = false;
    x.update(best.step, *direction, 1.0);
    after_step(d, fresh, best.step, point.energy - best.energy, iteration_began);
  }
  return std::nullopt;
}

void EnergyMinimizer::report_progress(Descent& d, double residual, double energy) const
{
  if (!log_ || now() - d.reported < 60.0) return;   // (only rank 0 has a log: no collective depends on this clock)
  d.reported = now();
  std::ostringstream line;   // formatted apart: the log's own format stays as it is
  line << "  descent: iteration " << d.iteration << ", |f| = " << std::scientific << std::setprecision(2) << residual
       << " nN, Pi = " << std::fixed << std::setprecision(4) << energy << " nN nm, " << std::setprecision(1)
       << (d.reported - d.began) / 60.0 << " min";
  *log_ << line.str() << std::endl;
}

MinimizerResult EnergyMinimizer::minimize(discretization::Vector& x, const DescentProgress* resumed,
                                          const Watch& watch)
{
  Descent d;
  if (resumed) {
    d.eta = resumed->shift;
    d.scale = resumed->scale;
    d.iteration = resumed->iterations;
  }
  auto start = model_.system().create_vector();
  start->assign(x);
  d.table << std::scientific << std::setprecision(2);
  if (tables_) d.table << "  descent  iteration  eta/scale  neg.piv   |f| [nN]       step  Pi [nN nm]\n";
  // After the solver failed to confirm a state with a small gradient (just past a fold the gradient is small but no
  // equilibrium is near), the descent goes on and asks again only at a gradient a thousand times smaller (the
  // minimum it then reaches can be very flat: a snapped-off face far out in the Lennard-Jones tail), up to three
  // times in all.
  double small_gradient = 1e-3;   // |f| [nN]
  auto confirmed = model_.system().create_vector();
  MinimizerResult result;
  for (int confirmations = 1;; ++confirmations) {
    std::optional<std::string> error;
    {
      const discretization::DescentLawScope descent_law(model_.system());
      error = uses_trust_region() ? descend_by_trust_region(x, d, small_gradient, watch)
                                  : descend_to_small_gradient(x, d, small_gradient, watch);
    }
    result.indefinite_tangents = d.indefinite;
    result.accepted_steps = d.accepted;
    if (error) {
      result.failure = *error;   // no state worth going on from
      return result;
    }
    if (log_ && tables_) *log_ << d.table.str();
    d.table.str("");
    if (d.iteration >= parameters_.maximum_iterations) {   // more iterations can go on from x
      start->update(1.0, x, -1.0);
      std::ostringstream reason;
      reason << "no stable state within " << parameters_.maximum_iterations << " iterations (" << d.accepted
             << " descent steps moved the state by at most " << std::setprecision(3) << start->normInf() << " nm; "
             << d.indefinite << " shifts for an indefinite tangent, " << d.no_decrease << " for no decrease of Pi; "
             << "final shift " << d.eta / d.scale << " x the mean diagonal)";
      result.failure = reason.str();
      result.can_go_on = true;
      return result;
    }
    confirmed->assign(x);
    // The give-up rules, a hopeless try ending soon, where the descent minimized the law's own energy; from the
    // minimum of its descent law's, Newton starts off its own equilibrium and gets all its iterations, and where it
    // does not converge there, the descent law's equilibrium is the state found (MinimizerResult::on_descent_law).
    auto& system = model_.system();
    auto plain = confirm_.solve(*confirmed, nullptr, !system.has_descent_law());
    if (!plain.converged && system.has_descent_law()) {
      const discretization::DescentLawScope descent_law(system);
      confirmed->assign(x);
      plain = confirm_.solve(*confirmed, nullptr, true);
      result.on_descent_law = plain.converged;
    }
    if (plain.converged) {
      x.assign(*confirmed);
      result.found = true;
      result.iterations = d.iteration + (plain.iterations.empty() ? 0 : plain.iterations.back().iteration);
      return result;
    }
    if (confirmations == 3) {
      result.failure = "Newton did not confirm the state the energy descent reached (" + plain.failure + ")";
      return result;
    }
    small_gradient = 1e-3 * std::min(small_gradient, d.residual);
    if (tables_) d.table << "  descent  (Newton did not confirm: " << plain.failure << "; descending further)\n";
  }
}

}  // namespace spatula::solvers
