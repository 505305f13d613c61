// Solid assembly and Newton iteration timings on the spatula (no adhesion, the pad held at Z = 0).
//
//   solid_benchmark <level> <linear solver> [repetitions]     (run with mpiexec -np 1 or 2)
//
// Prints one CSV line: medians over `repetitions` of the residual-only and residual+tangent assembly, the
// resulting element throughput, the effective memory traffic of the tangent fill against a STREAM-like triad
// measured in the same run, and the time of one Newton iteration split into assembly and linear solve.
#include "load_stepping.hpp"
#include "spatula_mesher.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_GlobalMPISession.hpp>
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

}  // namespace

int main(int argc, char** argv)
{
  Teuchos::GlobalMPISession session(&argc, &argv, nullptr);
  auto comm = Teuchos::DefaultComm<int>::getComm();
  if (argc < 3) {
    std::cerr << "usage: solid_benchmark <coarse|medium|fine> <mumps|gmres-ilu> [repetitions]\n";
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
  linear_parameters.type = solver_type;
  solvers::LinearSolverFactory linear(linear_parameters);
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  solvers::NewtonSolver newton(model, solvers::NewtonParameters{}, linear);
  const double bandwidth = triad_bandwidth();

  // One converged rotation step first (2.5 deg), so the timings are taken on a deformed state.
  analysis::LoadPath path(*model, newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = steps.maximum = 2.5;
  const double degree = 3.14159265358979323846 / 180.0;
  if (path.advance(discretization::Master::rotation, 2.5 * degree, analysis::LoadPath::spatula_control(discretization::Master::rotation, true), steps, degree, {})) return 3;

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
  if (path.advance(discretization::Master::rotation, 5.0 * degree, analysis::LoadPath::spatula_control(discretization::Master::rotation, true), steps, degree, {})) return 3;
  const double newton_seconds = seconds(newton_start);
  const double assembly_seconds = timer_total("spatula: assembly bulk (residual + tangent)") +
                                  timer_total("spatula: assembly bulk (residual)") +
                                  timer_total("spatula: assembly communication") - assembly_before;
  int iterations = 0;
  for (std::size_t i = points_before; i < path.points().size(); ++i) iterations += path.points()[i].newton_iterations;

  const auto entries = system->jacobian()->getGlobalNumEntries();
  const double bytes_per_fill = double(entries) * (8.0 + 4.0);   // values and column indices of the matrix
  if (root) {
    std::cout << "level,ranks,solver,elements,unknowns,matrix_entries,residual_s,tangent_s,residual_elements_per_s,"
                 "tangent_elements_per_s,tangent_fill_GBps,triad_GBps_per_rank,newton_iterations,"
                 "newton_s_per_iteration,assembly_s_per_iteration,linear_s_per_iteration\n";
    const double r = median(residual_times), t = median(tangent_times);
    std::cout << level << "," << comm->getSize() << "," << solver_type << "," << mesh.element_count() << ","
              << system->owned_map()->getGlobalNumElements() << "," << entries << "," << r << "," << t << ","
              << mesh.element_count() / r << "," << mesh.element_count() / t << "," << bytes_per_fill / t / 1e9 << ","
              << bandwidth / 1e9 << "," << iterations << "," << newton_seconds / iterations << ","
              << assembly_seconds / iterations << "," << (newton_seconds - assembly_seconds) / iterations << "\n";
  }
  return 0;
}
