#pragma once
// When kept factors are renewed: the one rule of Newton's linear solver (refactor = cost) and of the energy
// minimizer's descent (refactor = cost).
//
// A cycle is one factorization and the uses its factors serve; each use has a cost (work or seconds) and a yield
// (a tangent solved, or the decrease of the energy). The factors serve the next use while the last one yielded at
// least as much per unit of cost as the cycle has on average; renewing when the marginal rate falls to the average
// keeps the long-run rate near its best (uses get dearer or poorer as the factors age), and it adapts by itself: a
// cheap factorization is renewed often, a dear one rarely.
//
//   Newton (refactor = cost): factored(factorization work, 0), then keep(solve work of each tangent, 1): a tangent
//   is kept while its solves cost no more than the cycle's average per tangent.
//   The descent: factored(seconds of the fresh iteration, its decrease of Pi), then keep(seconds, decrease) of each
//   iteration served by kept factors; an iteration that lowers nothing ends the cycle.
namespace spatula::solvers {

class RenewalRule {
public:
  void factored(double cost, double yield);   // a new cycle: the factorization and its first use
  // The last use's cost and yield; true: the factors serve the next use too. False before any factorization.
  bool keep(double cost, double yield);
  int uses() const { return uses_; }          // in this cycle, those kept and the factorization's own

private:
  double cost_ = 0.0, yield_ = 0.0;
  int uses_ = 0;
};

}  // namespace spatula::solvers
