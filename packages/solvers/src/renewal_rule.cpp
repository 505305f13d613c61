#include "solvers/renewal_rule.hpp"

namespace spatula::solvers {

void RenewalRule::factored(double cost, double yield)
{
  cost_ = cost;
  yield_ = yield;
  uses_ = 1;
}

bool RenewalRule::keep(double cost, double yield)
{
  if (uses_ == 0) return false;   // nothing factored yet
  // yield / cost >= yield_ / cost_ (the cycle before this use; by the mediant, the same as the cycle with it)
  const bool keep = yield > 0.0 && yield * cost_ >= yield_ * cost;
  cost_ += cost;
  yield_ += yield;
  if (keep) ++uses_;
  return keep;
}

}  // namespace spatula::solvers
