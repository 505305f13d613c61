#pragma once
// How a run uses the machine it is given: the threads of its BLAS library (the program sets them itself, one per
// rank unless told otherwise, so that `mpirun -np 2 spatula` does not start a BLAS thread per core on every rank),
// and how long it may take, after a signal to stop, to reach the converged state it stops at (the watchdog).
#include <Teuchos_ParameterList.hpp>

#include <string>

namespace spatula::app {

struct JobParameters {
  int blas_threads = 0;        // 0: OPENBLAS_NUM_THREADS where set, else 1
  double stop_grace = 600.0;   // seconds from a stop signal to the end of the process at the latest
  static void declare(Teuchos::ParameterList& job);
  static JobParameters from(const Teuchos::ParameterList& job);
};

// Sets the BLAS library's thread count of this rank from the parameter (see blas_threads) and returns a line for the
// log: the threads each rank uses for BLAS (and where that count comes from) and for Kokkos (its backend).
std::string set_threads(const JobParameters& job);

}  // namespace spatula::app
