#include "analysis/instability_policy.hpp"

#include <stdexcept>

namespace spatula::analysis {

namespace {

class Stop : public InstabilityPolicy {
public:
  bool jumps() const override { return false; }
  bool counts_snaps_as_jumps() const override { return false; }
  std::optional<std::variant<double, Failure>> pass(LoadPath&, const LoadPath::Fold&,
                                                   const LoadPath::Callback&) const override
  {
    return std::nullopt;
  }
};

class Jump : public InstabilityPolicy {
public:
  bool jumps() const override { return true; }
  bool counts_snaps_as_jumps() const override { return true; }
  std::optional<std::variant<double, Failure>> pass(LoadPath& path, const LoadPath::Fold& fold,
                                                   const LoadPath::Callback& on_point) const override
  {
    return path.jump_past(fold, on_point);
  }
};

// Round a fold as the load rises (a fold met while the load falls stops the path, as with Stop).
class ArcLength : public InstabilityPolicy {
public:
  explicit ArcLength(const ArcLengthParameters& parameters) : parameters_(parameters) {}
  bool jumps() const override { return false; }
  bool counts_snaps_as_jumps() const override { return true; }
  std::optional<std::variant<double, Failure>> pass(LoadPath& path, const LoadPath::Fold& fold,
                                                   const LoadPath::Callback& on_point) const override
  {
    if (fold.direction <= 0) return std::nullopt;
    return path.continue_past(fold, parameters_, on_point);
  }

private:
  ArcLengthParameters parameters_;
};

}  // namespace

InstabilityPolicies& InstabilityPolicies::instance()
{
  static InstabilityPolicies registry;
  return registry;
}

InstabilityPolicies::InstabilityPolicies()
{
  factories_["stop"] = [](const ArcLengthParameters&) { return std::make_shared<const Stop>(); };
  factories_["jump"] = [](const ArcLengthParameters&) { return std::make_shared<const Jump>(); };
  factories_["arc-length"] = [](const ArcLengthParameters& p) { return std::make_shared<const ArcLength>(p); };
}

std::vector<std::string> InstabilityPolicies::names() const
{
  std::vector<std::string> names;
  for (const auto& [name, factory] : factories_) names.push_back(name);
  return names;
}

std::shared_ptr<const InstabilityPolicy> InstabilityPolicies::make(const std::string& name,
                                                                   const ArcLengthParameters& arc_length) const
{
  const auto found = factories_.find(name);
  if (found == factories_.end()) throw std::logic_error("no instability policy '" + name + "'");
  return found->second(arc_length);
}

void InstabilityPolicies::add(const std::string& name, Factory factory) { factories_[name] = std::move(factory); }

}  // namespace spatula::analysis
