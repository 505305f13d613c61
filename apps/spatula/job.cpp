#include "job.hpp"

#include "parameters/parameter_validation.hpp"

#include <Kokkos_Core.hpp>

#include <cstdlib>
#include <sstream>

#include <dlfcn.h>

namespace spatula::app {

void JobParameters::declare(Teuchos::ParameterList& job)
{
  const JobParameters d;
  parameters::declare_int(job, "BLAS threads", d.blas_threads,
                          "threads of the BLAS library per rank (the dense kernels of the direct solver); 0: the "
                          "environment's OPENBLAS_NUM_THREADS where set, else 1 (one rank per core is the efficient "
                          "use of a machine; more threads than cores slow every rank down)",
                          parameters::Range::closed(0, 1024));
  parameters::declare_double(job, "stop grace", d.stop_grace,
                             "seconds a run may take after a signal to stop (SIGTERM, SIGINT, SIGHUP, SIGQUIT, "
                             "SIGUSR1, SIGUSR2, SIGXCPU) to reach the converged state it stops at; past them a watchdog "
                             "ends the process, keeping the last checkpoint (a solve that does not return, or a step "
                             "longer than a batch system's warning); 0: no watchdog",
                             parameters::Range::closed(0.0, 86400.0 * 7));
}

JobParameters JobParameters::from(const Teuchos::ParameterList& job)
{
  JobParameters p;
  p.blas_threads = job.get<int>("BLAS threads");
  p.stop_grace = job.get<double>("stop grace");
  return p;
}

std::string set_threads(const JobParameters& job)
{
  int threads = job.blas_threads;
  std::string source = "'Job/BLAS threads'";
  if (threads == 0) {
    const char* environment = std::getenv("OPENBLAS_NUM_THREADS");
    const int from_environment = environment ? std::atoi(environment) : 0;
    threads = from_environment > 0 ? from_environment : 1;
    source = from_environment > 0 ? "OPENBLAS_NUM_THREADS" : "the default, one per rank";
  }
  // The BLAS in use is the one the dynamic linker chose (Debian's alternatives): OpenBLAS and BLIS can be told their
  // thread count; a reference BLAS has one thread.
  std::ostringstream line;
  line << "threads per rank: BLAS ";
  using SetThreads = void (*)(int);
  using GetThreads = int (*)();
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) {
    set(threads);
    auto get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    line << (get ? get() : threads) << " (OpenBLAS, " << source << ")";
  } else if (auto set_blis = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "bli_thread_set_num_threads"))) {
    set_blis(threads);
    line << threads << " (BLIS, " << source << ")";
  } else {
    line << "1 (a BLAS without threads)";
  }
  line << ", Kokkos " << Kokkos::DefaultExecutionSpace().concurrency() << " (" << Kokkos::DefaultExecutionSpace::name()
       << ")";
  return line.str();
}

}  // namespace spatula::app
