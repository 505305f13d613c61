#include "solvers/front_elimination.hpp"

#include "parameters/parameter_validation.hpp"
#include "solvers/energy_line_search.hpp"
#include "solvers/mumps_solver.hpp"

#include <NOX_Abstract_Group.H>
#include <NOX_Direction_Newton.H>
#include <NOX_Solver_LineSearchBased.H>
#include <NOX_Thyra_Vector.H>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace spatula::solvers {

using discretization::GlobalOrdinal;
using discretization::LocalOrdinal;
using discretization::Node;
using discretization::Vector;
using Extract = Thyra::TpetraOperatorVectorExtraction<double, LocalOrdinal, GlobalOrdinal, Node>;

const std::vector<std::string>& elimination_use_names()
{
  static const std::vector<std::string> names = {"never", "before the direction", "after the full step", "soft mode",
                                                 "front-limited step"};
  return names;
}

void FrontEliminationParameters::declare(Teuchos::ParameterList& list)
{
  const FrontEliminationParameters d;
  using parameters::Range;
  parameters::declare_string(list, "use", parameters::name_of(d.use, elimination_use_names()),
                             "when the front is relaxed: never, before the direction (at every Newton iteration "
                             "but the first, before Newton's direction is computed) or after the full step (where "
                             "Newton's full step passed the energy's minimum along its line, from that step, before "
                             "the energy line search would cut it); or, instead of relaxing it, front-limited step: "
                             "Newton's step corrected so that the contact points it would carry outward past the "
                             "law's inflection reach it (in the integral) and the rest of the body follows (one "
                             "more linear solve per iteration)",
                             elimination_use_names());
  parameters::declare_double(list, "node share", d.node_share,
                             "a node is relaxed where its residual |f_node| is at least this share of the largest",
                             {0.0, 1.0, true, false});
  parameters::declare_int(list, "maximum nodes", d.maximum_nodes,
                          "nodes relaxed at most (the largest residuals first)", Range::closed(1, 5000));
  parameters::declare_int(list, "iterations", d.iterations,
                          "local Newton iterations per relaxation (each one tangent evaluation)", Range::closed(1, 50));
  parameters::declare_double(list, "reduction", d.reduction,
                             "the relaxation stops once the front's |f| is this share of its start or below the "
                             "residual of the other unknowns", {0.0, 1.0, true, false});
  parameters::declare_double(list, "beyond inflection", d.beyond_inflection,
                             "front-limited step: how far past the law's inflection (its strongest attraction) the "
                             "points a Newton step would release are let go [nm]",
                             {0.0, 10.0, false, false});
}

FrontEliminationParameters FrontEliminationParameters::from(const Teuchos::ParameterList& list)
{
  FrontEliminationParameters p;
  p.use = parameters::choice<EliminationUse>(list, "use", elimination_use_names());
  p.node_share = list.get<double>("node share");
  p.maximum_nodes = list.get<int>("maximum nodes");
  p.iterations = list.get<int>("iterations");
  p.reduction = list.get<double>("reduction");
  p.beyond_inflection = list.get<double>("beyond inflection");
  return p;
}

namespace {

// The unknowns relaxed: those of the nodes whose residual |f_node| is at least `share` of the largest, at most
// `maximum` nodes (largest first, ties by node), in ascending global order; the same list on every rank.
std::vector<GlobalOrdinal> front_unknowns(const discretization::DiscreteSystem& system, const Vector& f,
                                          const FrontEliminationParameters& parameters, int& node_count)
{
  node_count = 0;
  const auto& layout = system.layout();
  const auto map = f.getMap();
  const auto values = f.getData();
  const std::size_t nodes = layout.node_dofs.size();
  std::vector<double> local(nodes, 0.0), squares(nodes, 0.0);
  for (std::size_t node = 0; node < nodes; ++node)
    for (const auto dof : layout.node_dofs[node]) {
      if (dof == discretization::DofLayout::fixed) continue;
      const auto index = map->getLocalElement(dof);
      if (index == Teuchos::OrdinalTraits<LocalOrdinal>::invalid()) continue;
      local[node] += values[index] * values[index];
    }
  Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, static_cast<int>(nodes), local.data(), squares.data());
  const double largest = *std::max_element(squares.begin(), squares.end());
  if (!(largest > 0.0)) return {};
  std::vector<std::size_t> chosen;
  for (std::size_t node = 0; node < nodes; ++node)
    if (squares[node] >= parameters.node_share * parameters.node_share * largest) chosen.push_back(node);
  std::stable_sort(chosen.begin(), chosen.end(),
                   [&](std::size_t a, std::size_t b) { return squares[a] > squares[b]; });
  if (chosen.size() > static_cast<std::size_t>(parameters.maximum_nodes)) chosen.resize(parameters.maximum_nodes);
  node_count = static_cast<int>(chosen.size());
  std::vector<GlobalOrdinal> unknowns;
  for (const auto node : chosen)
    for (const auto dof : layout.node_dofs[node])
      if (dof != discretization::DofLayout::fixed) unknowns.push_back(dof);
  std::sort(unknowns.begin(), unknowns.end());
  return unknowns;
}

// The front's block of the tangent (row-major, m x m) and its residual, complete on every rank: each rank writes the
// rows it owns, a sum over the ranks completes them (every entry has one writer).
void gather_block(const discretization::CrsMatrix& tangent, const Vector& f, const std::vector<GlobalOrdinal>& unknowns,
                  const std::unordered_map<GlobalOrdinal, int>& position, std::vector<double>& matrix,
                  std::vector<double>& residual)
{
  const int m = static_cast<int>(unknowns.size());
  std::vector<double> local(static_cast<std::size_t>(m) * (m + 1), 0.0);
  const auto row_map = tangent.getRowMap();
  const auto column_map = tangent.getColMap();
  const auto values = f.getData();
  for (int i = 0; i < m; ++i) {
    const auto row = row_map->getLocalElement(unknowns[i]);
    if (row == Teuchos::OrdinalTraits<LocalOrdinal>::invalid()) continue;
    typename discretization::CrsMatrix::local_inds_host_view_type indices;
    typename discretization::CrsMatrix::values_host_view_type entries;
    tangent.getLocalRowView(row, indices, entries);
    for (std::size_t k = 0; k < indices.extent(0); ++k) {
      const auto found = position.find(column_map->getGlobalElement(indices(k)));
      if (found != position.end()) local[static_cast<std::size_t>(i) * m + found->second] += entries(k);
    }
    local[static_cast<std::size_t>(m) * m + i] = values[f.getMap()->getLocalElement(unknowns[i])];
  }
  std::vector<double> total(local.size(), 0.0);
  Teuchos::reduceAll(*f.getMap()->getComm(), Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(),
                     total.data());
  matrix.assign(total.begin(), total.begin() + static_cast<std::ptrdiff_t>(m) * m);
  residual.assign(total.begin() + static_cast<std::ptrdiff_t>(m) * m, total.end());
}

// Sum over the ranks of sum_i a[unknown_i] b_i for the unknowns this rank owns.
double front_dot(const Vector& a, const std::vector<GlobalOrdinal>& unknowns, const std::vector<double>& b)
{
  const auto map = a.getMap();
  const auto values = a.getData();
  double local = 0.0, total = 0.0;
  for (std::size_t i = 0; i < unknowns.size(); ++i) {
    const auto index = map->getLocalElement(unknowns[i]);
    if (index != Teuchos::OrdinalTraits<LocalOrdinal>::invalid()) local += values[index] * b[i];
  }
  Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, 1, &local, &total);
  return total;
}

// x = origin + step d on the front's unknowns this rank owns.
void move_front(Vector& x, const Vector& origin, const std::vector<GlobalOrdinal>& unknowns,
                const std::vector<double>& direction, double step)
{
  x.assign(origin);
  const auto map = x.getMap();
  auto values = x.getDataNonConst();
  const auto start = origin.getData();
  for (std::size_t i = 0; i < unknowns.size(); ++i) {
    const auto index = map->getLocalElement(unknowns[i]);
    if (index != Teuchos::OrdinalTraits<LocalOrdinal>::invalid()) values[index] = start[index] + step * direction[i];
  }
}

}  // namespace

bool relax_front(const SpatulaModel& model, Vector& x, Vector& f, const FrontEliminationParameters& parameters,
               EliminationCounts& counts)
{
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: front elimination"));
  int node_count = 0;
  const auto unknowns = front_unknowns(model.system(), f, parameters, node_count);
  if (unknowns.empty()) return false;
  std::unordered_map<GlobalOrdinal, int> position;
  for (std::size_t i = 0; i < unknowns.size(); ++i) position.emplace(unknowns[i], static_cast<int>(i));
  const int m = static_cast<int>(unknowns.size());

  const auto front_norm = [&](const Vector& residual) {
    const auto map = residual.getMap();
    const auto values = residual.getData();
    double local = 0.0, total = 0.0;
    for (int i = 0; i < m; ++i) {
      const auto index = map->getLocalElement(unknowns[i]);
      if (index != Teuchos::OrdinalTraits<LocalOrdinal>::invalid()) local += values[index] * values[index];
    }
    Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, 1, &local, &total);
    return std::sqrt(total);
  };
  const auto rest_norm = [&](const Vector& residual, double front) {
    const double all = residual.norm2();
    return std::sqrt(std::max(0.0, all * all - front * front));
  };
  const double start = front_norm(f);
  double front = start;
  if (front <= rest_norm(f, front)) return false;   // the residual is not the front's

  ++counts.applications;
  counts.last_nodes = node_count;
  bool moved = false;
  Vector origin(x, Teuchos::Copy);
  std::vector<double> matrix, direction;
  Teuchos::LAPACK<int, double> lapack;
  for (int iteration = 0; iteration < parameters.iterations; ++iteration) {
    if (!model.evaluate(x, &f, true).admissible) break;
    gather_block(*model.system().jacobian(), f, unknowns, position, matrix, direction);
    for (auto& value : direction) value = -value;
    std::vector<int> pivots(m);
    int info = 0;
    lapack.GESV(m, 1, matrix.data(), m, pivots.data(), direction.data(), m, &info);   // (row-major: W symmetric)
    if (info != 0) break;
    const double energy = model.last_evaluation().energy();
    const LinePoint line_origin{0.0, front_dot(f, unknowns, direction), energy, true};
    if (!(line_origin.slope < 0.0)) break;   // not a descent direction for the front (an indefinite block)
    origin.assign(x);
    double evaluated = 0.0;
    const auto evaluate = [&](double step) {
      move_front(x, origin, unknowns, direction, step);
      const auto& evaluation = model.evaluate(x, &f, false);
      evaluated = step;
      return LinePoint{step, evaluation.admissible ? front_dot(f, unknowns, direction) : 0.0, evaluation.energy(),
                       evaluation.admissible};
    };
    const LinePoint chosen = search_energy_line(evaluate, line_origin, EnergyLineSearchParameters{});
    if (!chosen.admissible) {
      x.assign(origin);
      break;
    }
    if (chosen.step != evaluated) evaluate(chosen.step);
    ++counts.local_iterations;
    moved = true;
    front = front_norm(f);
    if (front <= parameters.reduction * start || front <= rest_norm(f, front)) break;
  }
  counts.last_reduction = start > 0.0 ? front / start : 1.0;
  return moved;
}

namespace {

class FrontElimination : public NOX::Direction::Generic {
public:
  FrontElimination(const Teuchos::RCP<NOX::GlobalData>& data, Teuchos::ParameterList& list, const SpatulaModel& model,
                   const FrontEliminationParameters& parameters, EliminationCounts& counts)
      : newton_(data, list), model_(model), parameters_(parameters), counts_(counts),
        linear_tolerance_(list.sublist("Newton").sublist("Linear Solver").get<double>("Tolerance", 1e-8))
  {
  }

  bool reset(const Teuchos::RCP<NOX::GlobalData>& data, Teuchos::ParameterList& list) override
  {
    return newton_.reset(data, list);
  }
  bool compute(NOX::Abstract::Vector& direction, NOX::Abstract::Group& group,
               const NOX::Solver::Generic& solver) override
  {
    if (wanted(solver)) relax(group);
    if (parameters_.use == EliminationUse::soft_mode && solver.getNumIterations() > 0) along_soft_mode(group);
    if (!newton_.compute(direction, group, solver)) return false;
    if (parameters_.use == EliminationUse::soft_mode && solver.getNumIterations() == 0) find_soft_mode();
    if (parameters_.use == EliminationUse::front_limited_step) limit_front(direction, group);
    return true;
  }
  bool compute(NOX::Abstract::Vector& direction, NOX::Abstract::Group& group,
               const NOX::Solver::LineSearchBased& solver) override
  {
    if (wanted(solver)) relax(group);
    if (parameters_.use == EliminationUse::soft_mode && solver.getNumIterations() > 0) along_soft_mode(group);
    if (!newton_.compute(direction, group, solver)) return false;
    if (parameters_.use == EliminationUse::soft_mode && solver.getNumIterations() == 0) find_soft_mode();
    if (parameters_.use == EliminationUse::front_limited_step) limit_front(direction, group);
    return true;
  }

private:
  bool wanted(const NOX::Solver::Generic& solver) const
  {
    return parameters_.use == EliminationUse::before_direction && solver.getNumIterations() > 0;
  }

  // The tangent's softest mode at the attempt's start (inverse iteration on its own factors).
  void find_soft_mode()
  {
    const auto& tangent = *model_.system().jacobian();
    const auto map = tangent.getRowMap();
    if (!soft_solver_) soft_solver_ = std::make_unique<MumpsSolver>(map, MumpsParameters{}.exact_ldlt());
    soft_solver_->factor(tangent);
    soft_ = Teuchos::rcp(new Vector(map));
    Vector z(map), product(map);
    {
      auto values = soft_->getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t i = 0; i < values.extent(0); ++i)
        values(i, 0) = 1.0 + 0.5 * std::sin(0.7 * static_cast<double>(map->getGlobalElement(static_cast<LocalOrdinal>(i))));
    }
    soft_->scale(1.0 / soft_->norm2());
    for (int k = 0; k < 8; ++k) {
      soft_solver_->apply(*soft_, z);
      soft_->update(1.0 / z.norm2(), z, 0.0);
    }
    tangent.apply(*soft_, product);
    soft_value_ = soft_->dot(product);
  }

  // An energy line search along the soft mode from the group's state.
  void along_soft_mode(NOX::Abstract::Group& group)
  {
    if (soft_.is_null() || !(soft_value_ > 0.0)) return;
    if (!group.isF()) group.computeF();
    const auto& thyra_x = dynamic_cast<const NOX::Thyra::Vector&>(group.getX());
    const auto& thyra_f = dynamic_cast<const NOX::Thyra::Vector&>(group.getF());
    const Vector origin(*Extract::getConstTpetraVector(thyra_x.getThyraRCPVector()), Teuchos::Copy);
    const Vector& f0 = *Extract::getConstTpetraVector(thyra_f.getThyraRCPVector());
    const double slope = f0.dot(*soft_);
    Vector step(*soft_, Teuchos::Copy);
    step.scale(-slope / soft_value_);   // the quadratic model's minimizer along the mode
    const double energy = model_.evaluate(origin, nullptr, false).energy();
    const LinePoint line_origin{0.0, -slope * slope / soft_value_, energy, true};
    if (!(line_origin.slope < 0.0)) return;
    auto x = Teuchos::rcp(new Vector(origin, Teuchos::Copy));
    Vector f(origin.getMap());
    double evaluated = 0.0;
    const auto evaluate = [&](double alpha) {
      x->update(1.0, origin, alpha, step, 0.0);
      const auto& evaluation = model_.evaluate(*x, &f, false);
      evaluated = alpha;
      return LinePoint{alpha, evaluation.admissible ? f.dot(step) : 0.0, evaluation.energy(), evaluation.admissible};
    };
    const LinePoint chosen = search_energy_line(evaluate, line_origin, EnergyLineSearchParameters{});
    if (!chosen.admissible || !(chosen.energy < energy)) return;
    if (chosen.step != evaluated) evaluate(chosen.step);
    ++counts_.applications;
    counts_.last_nodes = 0;
    counts_.last_reduction = chosen.step * std::abs(slope) / soft_value_;   // the distance moved along the mode
    group.setX(NOX::Thyra::Vector(Thyra::createVector(x, thyra_x.getThyraRCPVector()->space())));
  }

  // Newton's step d becomes d + lambda K^-1 c with c . (d + lambda K^-1 c) = t: the points d would carry outward
  // past the limit reach it in the integral (c, t: DiscreteSystem::contact_gap_limit), by one more solve with the
  // group's tangent and its solver (its factors or kept factors, as Newton's own solve).
  void limit_front(NOX::Abstract::Vector& direction, NOX::Abstract::Group& group)
  {
    const auto& thyra_x = dynamic_cast<const NOX::Thyra::Vector&>(group.getX());
    const auto& thyra_d = dynamic_cast<const NOX::Thyra::Vector&>(direction);
    const Vector& x = *Extract::getConstTpetraVector(thyra_x.getThyraRCPVector());
    Vector full(x, Teuchos::Copy);
    full.update(1.0, *Extract::getConstTpetraVector(thyra_d.getThyraRCPVector()), 1.0);
    auto row = Teuchos::rcp(new Vector(x.getMap()));
    const auto limit = model_.system().contact_gap_limit(x, full, parameters_.beyond_inflection, *row);
    if (limit.points == 0) return;
    const NOX::Thyra::Vector c(Thyra::createVector(row, thyra_x.getThyraRCPVector()->space()));
    auto z = c.clone(NOX::ShapeCopy);
    Teuchos::ParameterList solve;
    solve.set("Tolerance", linear_tolerance_);
    if (group.applyJacobianInverse(solve, c, *z) != NOX::Abstract::Group::Ok) return;
    const double cz = c.innerProduct(*z), cd = c.innerProduct(direction);
    if (!(cz > 0.0) || !(cd > limit.target)) return;
    const double lambda = (limit.target - cd) / cz;
    direction.update(lambda, *z, 1.0);
    ++counts_.limited_steps;
    counts_.last_limited_points = limit.points;
    counts_.last_kept = limit.target / cd;
  }

  // The group's state becomes the relaxed one.
  void relax(NOX::Abstract::Group& group)
  {
    if (!group.isF()) group.computeF();
    const auto& thyra_x = dynamic_cast<const NOX::Thyra::Vector&>(group.getX());
    const auto& thyra_f = dynamic_cast<const NOX::Thyra::Vector&>(group.getF());
    auto x = Teuchos::rcp(new Vector(*Extract::getConstTpetraVector(thyra_x.getThyraRCPVector()), Teuchos::Copy));
    Vector f(*Extract::getConstTpetraVector(thyra_f.getThyraRCPVector()), Teuchos::Copy);
    if (relax_front(model_, *x, f, parameters_, counts_))
      group.setX(NOX::Thyra::Vector(Thyra::createVector(x, thyra_x.getThyraRCPVector()->space())));
  }

  NOX::Direction::Newton newton_;
  std::unique_ptr<MumpsSolver> soft_solver_;
  Teuchos::RCP<Vector> soft_;
  double soft_value_ = 0.0;
  const SpatulaModel& model_;
  FrontEliminationParameters parameters_;
  EliminationCounts& counts_;
  double linear_tolerance_;
};

}  // namespace

Teuchos::RCP<NOX::Direction::Generic> FrontEliminationFactory::buildDirection(
    const Teuchos::RCP<NOX::GlobalData>& data, Teuchos::ParameterList& list) const
{
  return Teuchos::rcp(new FrontElimination(data, list, model_, parameters_, counts_));
}

}  // namespace spatula::solvers
