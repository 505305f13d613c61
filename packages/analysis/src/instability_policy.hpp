#pragma once
// What a load path does where no equilibrium follows at a larger load (a fold of the path, an instability), chosen by
// name ('Loading/past instabilities'): stop there; jump at fixed load to the next stable state by energy descent; or
// follow the path round the fold by arc-length continuation. The load path offers the means (LoadPath::jump_past,
// LoadPath::continue_past); a policy chooses among them. A registry like the contact laws: a new policy is a class
// and a line in InstabilityPolicies' constructor (or InstabilityPolicies::add at run time).
#include "analysis/load_stepping.hpp"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace spatula::analysis {

class InstabilityPolicy {
public:
  virtual ~InstabilityPolicy() = default;
  // Whether it jumps at fixed load by energy descent: only then does the path try early descents after failed
  // attempts and take up a checkpointed jump.
  virtual bool jumps() const = 0;
  // Whether a snap that even the smallest step crosses is counted as a jump (else the path stops there).
  virtual bool counts_snaps_as_jumps() const = 0;
  // Past `fold`: the controlled load's value beyond it (stepping resumes there) or why the path stops; nothing where
  // the policy does not pass this fold (the path stops with Newton's failure).
  virtual std::optional<std::variant<double, Failure>> pass(LoadPath& path, const LoadPath::Fold& fold,
                                                           const LoadPath::Callback& on_point) const = 0;
};

class InstabilityPolicies {
public:
  using Factory = std::function<std::shared_ptr<const InstabilityPolicy>(const ArcLengthParameters&)>;
  static InstabilityPolicies& instance();
  std::vector<std::string> names() const;   // "arc-length", "jump", "stop", and those added
  // The policy of this name (InputError-free: the name was validated against names()); `arc_length`: the
  // continuation's steps, for the policies that use it.
  std::shared_ptr<const InstabilityPolicy> make(const std::string& name, const ArcLengthParameters& arc_length) const;
  void add(const std::string& name, Factory factory);

private:
  InstabilityPolicies();
  std::map<std::string, Factory> factories_;
};

}  // namespace spatula::analysis
