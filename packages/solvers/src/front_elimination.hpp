#pragma once
// Nonlinear elimination of the peel front (Cai and Li 2011, one level): before a Newton direction is computed, the
// few nodes where the residual concentrates (the front's contact points crossing the Lennard-Jones law's range, after
// a global step the energy line search had to cut) are relaxed by a local Newton iteration with every other unknown
// frozen; the global Newton step then starts from a state whose front is in equilibrium with the rest, and sees
// a nearly linear problem. The local system is the tangent's block on those nodes, gathered to every rank and
// solved densely (a few hundred unknowns), each local step with the energy line search.
// The front-limited step (use = front-limited step) treats the same points by a constraint instead: Newton's step d
// would carry some contact points outward past the law's inflection; d + lambda K^-1 c, with c the integral of their
// gaps' gradient, brings them (in the integral) only to the inflection plus `beyond inflection`, the rest of the
// body following consistently (one more solve with the tangent's solver per iteration).
#include "solvers/spatula_model.hpp"

#include <NOX_Direction_UserDefinedFactory.H>

#include <string>
#include <vector>

namespace Teuchos { class ParameterList; }

namespace spatula::solvers {

enum class EliminationUse { never, before_direction, after_full_step, soft_mode, front_limited_step };   // in the order of elimination_use_names()
const std::vector<std::string>& elimination_use_names();

struct FrontEliminationParameters {
  EliminationUse use = EliminationUse::never;
  double node_share = 0.1;     // a node is eliminated where its residual is at least this share of the largest
  int maximum_nodes = 200;     // ... at most this many, the largest residuals first
  int iterations = 4;          // local Newton iterations (each one tangent evaluation)
  double reduction = 0.1;      // stop once the front's |f| is this share of its start, or below the rest's |f|
  double beyond_inflection = 0.0;   // front-limited step: where the released points stop, past the inflection [nm]

  static void declare(Teuchos::ParameterList& list);
  static FrontEliminationParameters from(const Teuchos::ParameterList& list);
};

// What the elimination did over one Newton solve, for the convergence table and the counts.
struct EliminationCounts {
  int applications = 0;        // Newton iterations that relaxed a front
  int local_iterations = 0;    // local Newton iterations (each one tangent)
  int last_nodes = 0;          // nodes relaxed at the last application
  double last_reduction = 1.0; // the front's |f| after over before, at the last application
  int limited_steps = 0;       // front-limited steps: Newton directions corrected
  int last_limited_points = 0;  // ... the points the last one held back
  double last_kept = 1.0;       // ... the share c . d' / c . d of their gap change it kept
};

// Relaxes the front of the state x, whose residual is f: the nodes whose |f_node| is at least 'node share' of the
// largest, while their residual exceeds the others', by local Newton iterations with the energy line search, the
// other unknowns frozen. Returns whether x moved; x and f then hold the relaxed state and its residual. Collective.
bool relax_front(const SpatulaModel& model, discretization::Vector& x, discretization::Vector& f,
                 const FrontEliminationParameters& parameters, EliminationCounts& counts);

// The NOX direction: the front's relaxation, then NOX's Newton direction at the relaxed state.
class FrontEliminationFactory : public NOX::Direction::UserDefinedFactory {
public:
  FrontEliminationFactory(const SpatulaModel& model, const FrontEliminationParameters& parameters,
                          EliminationCounts& counts)
      : model_(model), parameters_(parameters), counts_(counts)
  {
  }
  Teuchos::RCP<NOX::Direction::Generic> buildDirection(const Teuchos::RCP<NOX::GlobalData>& data,
                                                       Teuchos::ParameterList& list) const override;

private:
  const SpatulaModel& model_;
  FrontEliminationParameters parameters_;
  EliminationCounts& counts_;
};

}  // namespace spatula::solvers
