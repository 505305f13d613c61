// Solid assembly and Newton iteration timings on the spatula (no adhesion, the pad held at Z = 0).
//
//   solid_benchmark <level> <linear solver> [repetitions] [ordering=NAME] [low-rank=TOLERANCE] [precision=single] [lag=N]
//                   [refactor=cost|lag] [factor-only=1]                           (run with mpiexec -np 1 or 2)
//
// factor-only=1: just the MUMPS analysis, `repetitions` factorizations and a solve of the tangent at the undeformed
// state (fast comparison of orderings and low-rank tolerances on the fine mesh); prints one CSV line of its own.
//
// Prints one CSV line: medians over `repetitions` of the residual-only and residual+tangent assembly, the
// resulting element throughput, the effective memory traffic of the tangent fill against a STREAM-like triad
// measured in the same run, and the time of one Newton iteration split into assembly and linear solve.
#include "analysis/load_stepping.hpp"
#include "solvers/node_blocks.hpp"
#include "parameters/parameter_validation.hpp"
#include "mesh/spatula_mesher.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_GlobalMPISession.hpp>
#include <Tpetra_Core.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

using namespace spatula;

namespace {

double seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Bytes per second of a = b + s c over arrays much larger than the caches (per rank).
double triad_bandwidth()
{
  const std::size_t n = 20'000'000;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  std::vector<double> times;
  for (int repetition = 0; repetition < 5; ++repetition) {
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + 3.0 * c[i];
    times.push_back(seconds(start));
  }
  volatile double sink = a[n / 2];
  (void)sink;
  return 3.0 * 8.0 * n / median(times);
}

double timer_total(const std::string& name)
{
  return Teuchos::TimeMonitor::getNewTimer(name)->totalElapsedTime();
}

// Analysis, factorizations and one solve of the tangent at the undeformed state; one CSV line.
int factor_benchmark(discretization::DiscreteSystem& system, const solvers::MumpsParameters& parameters,
                     const std::string& level, int repetitions, const std::string& variant)
{
  const auto comm = system.owned_map()->getComm();
  auto x = system.create_vector();
  auto residual = system.create_vector();
  system.evaluate(*x, residual.get(), true);
  solvers::MumpsSolver mumps(system.owned_map(), parameters);
  std::vector<double> factor_times;
  for (int r = 0; r < std::max(repetitions, 1); ++r) {
    comm->barrier();
    const auto start = std::chrono::steady_clock::now();
    mumps.factor(*system.jacobian());
    comm->barrier();
    factor_times.push_back(seconds(start));
  }
  // Accuracy of one solve with these factors: |K u - f| / |f| for f = the residual at a rotated state.
  auto b = system.create_vector(), solution = system.create_vector(), check = system.create_vector();
  b->randomize();
  comm->barrier();
  const auto start = std::chrono::steady_clock::now();
  mumps.apply(*b, *solution);
  comm->barrier();
  const double solve_seconds = seconds(start);
  system.jacobian()->apply(*solution, *check);
  check->update(-1.0, *b, 1.0);
  const double relative_residual = check->norm2() / b->norm2();
  const auto& statistics = mumps.statistics();
  if (comm->getRank() == 0)
    std::cout << "level,ranks,options,unknowns,ordering_used,analysis_s,factorization_s_median,solve_s,"
                 "relative_residual_one_solve,factorization_gflop,factor_entries_millions,factorization_MB_all_ranks\n"
              << level << "," << comm->getSize() << "," << (variant.empty() ? "default" : variant) << ","
              << system.owned_map()->getGlobalNumElements() << "," << statistics.ordering_used << ","
              << statistics.analysis_seconds << "," << median(factor_times) << "," << solve_seconds << ","
              << relative_residual << "," << statistics.factorization_flops / 1e9 << ","
              << statistics.factor_entries / 1e6 << "," << statistics.factorization_megabytes << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  Teuchos::GlobalMPISession session(&argc, &argv, nullptr);
  Tpetra::ScopeGuard kokkos_scope(&argc, &argv);   // Kokkos starts here, not lazily at the first Tpetra::Map
  auto comm = Teuchos::DefaultComm<int>::getComm();
  if (argc < 3) {
    std::cerr << "usage: solid_benchmark <coarse|medium|fine> <mumps|gmres-ilu|gmres-amg> [repetitions] "
                 "[ordering=NAME] [low-rank=TOLERANCE] [precision=single] [lag=N]\n";
    return 2;
  }
  const std::string level = argv[1], solver_type = argv[2];
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 5;
  const bool root = comm->getRank() == 0;

  const geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  mesh::MeshParameters mesh_parameters;
  mesh_parameters.level = level;
  const auto mesh = mesh::mesh_spatula(shape, mesh_parameters);
  const auto partition = mesh::partition_mesh(mesh, comm->getSize());
  const auto p1 = shape.point(1);
  auto system = Teuchos::rcp(new discretization::DiscreteSystem(
      mesh, partition, discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, true), {}, comm));
  solvers::LinearSolverParameters linear_parameters;
  const auto type = parameters::choice_named<solvers::LinearSolverType>(solver_type, solvers::linear_solver_names());
  if (!type || *type == solvers::LinearSolverType::automatic) {
    std::cerr << "solid_benchmark: unknown linear solver '" << solver_type << "' (name one: auto is the app's)\n";
    return 2;
  }
  linear_parameters.type = *type;
  std::string variant;   // the MUMPS options given, for the CSV
  bool factor_only = false;
  for (int a = 4; a < argc; ++a) {
    const std::string option = argv[a];
    const auto equals = option.find('=');
    const std::string key = option.substr(0, equals), value = option.substr(equals + 1);
    const auto ordering = parameters::choice_named<solvers::MumpsOrdering>(value, solvers::mumps_ordering_names());
    const auto refactor = parameters::choice_named<solvers::RefactorRule>(value, solvers::refactor_rule_names());
    if (key == "ordering" && ordering)
      linear_parameters.mumps.ordering = *ordering;
    else if (key == "low-rank")
      linear_parameters.mumps.low_rank_tolerance = std::stod(value);
    else if (key == "precision" && (value == "single" || value == "double"))
      linear_parameters.mumps.single_precision = value == "single";
    else if (key == "lag")
      linear_parameters.lag = std::stoi(value);
    else if (key == "refactor" && refactor)
      linear_parameters.refactor = *refactor;
    else if (key == "factor-only")
      factor_only = value == "1";
    else {
      std::cerr << "solid_benchmark: unknown option '" << option << "'\n";
      return 2;
    }
    variant += (variant.empty() ? "" : " ") + option;
  }
  if (factor_only) return factor_benchmark(*system, linear_parameters.mumps, level, repetitions, variant);
  solvers::LinearSolverFactory linear(linear_parameters,
                                      std::make_shared<const solvers::NodeBlocks>(solvers::node_blocks(*system)));
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  solvers::NewtonSolver newton(model, solvers::NewtonParameters{}, linear);
  const double bandwidth = triad_bandwidth();

  // One converged rotation step first (2.5 deg), so the timings are taken on a deformed state.
  analysis::LoadPath path(*model, newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = steps.maximum = 2.5;
  const double degree = 3.14159265358979323846 / 180.0;
  if (path.advance(discretization::Master::rotation, 2.5 * degree, discretization::MasterControl::moving(discretization::Master::rotation, {discretization::Master::lift}), steps, degree, {})) return 3;

  auto residual = system->create_vector();
  std::vector<double> residual_times, tangent_times;
  for (int r = 0; r < repetitions; ++r) {
    comm->barrier();
    auto start = std::chrono::steady_clock::now();
    system->evaluate(path.state(), residual.get(), false);
    comm->barrier();
    residual_times.push_back(seconds(start));
    start = std::chrono::steady_clock::now();
    system->evaluate(path.state(), residual.get(), true);
    comm->barrier();
    tangent_times.push_back(seconds(start));
  }

  // Newton iterations of a second 2.5 deg step, split into assembly (with tangent) and the rest.
  const double assembly_before = timer_total("spatula: assembly bulk (residual + tangent)") +
                                 timer_total("spatula: assembly bulk (residual)") +
                                 timer_total("spatula: assembly communication");
  const auto newton_start = std::chrono::steady_clock::now();
  const std::size_t points_before = path.points().size();
  if (path.advance(discretization::Master::rotation, 5.0 * degree, discretization::MasterControl::moving(discretization::Master::rotation, {discretization::Master::lift}), steps, degree, {})) return 3;
  const double newton_seconds = seconds(newton_start);
  const double assembly_seconds = timer_total("spatula: assembly bulk (residual + tangent)") +
                                  timer_total("spatula: assembly bulk (residual)") +
                                  timer_total("spatula: assembly communication") - assembly_before;
  int iterations = 0;
  for (std::size_t i = points_before; i < path.points().size(); ++i) iterations += path.points()[i].newton_iterations;

  const auto entries = system->jacobian()->getGlobalNumEntries();
  const double bytes_per_fill = double(entries) * (8.0 + 4.0);   // values and column indices of the matrix
  const auto& statistics = linear.mumps_statistics();
  if (root) {
    std::cout << "level,ranks,solver,elements,unknowns,matrix_entries,residual_s,tangent_s,residual_elements_per_s,"
                 "tangent_elements_per_s,tangent_fill_GBps,triad_GBps_per_rank,newton_iterations,"
                 "newton_s_per_iteration,assembly_s_per_iteration,linear_s_per_iteration,options,ordering_used,"
                 "factorizations,factorization_s_median_last,factorization_gflop,factor_entries_millions,"
                 "factorization_MB_all_ranks\n";
    const double r = median(residual_times), t = median(tangent_times);
    std::cout << level << "," << comm->getSize() << "," << solver_type << "," << mesh.element_count() << ","
              << system->owned_map()->getGlobalNumElements() << "," << entries << "," << r << "," << t << ","
              << mesh.element_count() / r << "," << mesh.element_count() / t << "," << bytes_per_fill / t / 1e9 << ","
              << bandwidth / 1e9 << "," << iterations << "," << newton_seconds / iterations << ","
              << assembly_seconds / iterations << "," << (newton_seconds - assembly_seconds) / iterations << ","
              << (variant.empty() ? "default" : variant) << "," << statistics.ordering_used << ","
              << statistics.factorizations << "," << statistics.last_factorization_seconds << ","
              << statistics.factorization_flops / 1e9 << "," << statistics.factor_entries / 1e6 << ","
              << statistics.factorization_megabytes << "\n";
    const auto& multigrid = linear.multigrid_statistics();
    if (multigrid.setups > 0)
      std::cerr << "solid_benchmark: AMG " << multigrid.setups << " hierarchies, " << multigrid.reuses << " reused, "
                << multigrid.applications << " applications" << (multigrid.fell_back ? ", then MUMPS after a stalled solve" : "")
                << "\n";
  }
  return 0;
}
