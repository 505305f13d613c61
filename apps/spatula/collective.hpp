#pragma once
// Checks that one rank does (the output directory) or that could fail on one rank only (memory, files) end the
// same way on every rank: `agree` runs a check on the ranks that take part, and if any of them throws, every rank
// throws the same error (the first failing rank's message), so all ranks stop together with one exit code instead
// of one rank waiting forever in the next collective call.
//
// A failure inside the solution, where ranks are deep in collective calls, cannot be agreed on this way: there
// `abort_all` ends every rank at once with the given exit code.
#include <Teuchos_Comm.hpp>

#include <functional>
#include <stdexcept>

namespace spatula::app {

// An error that every rank has raised together (after `agree`): no rank is left waiting.
class AgreedFailure : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Runs `check` on every rank (or on rank 0 only) and throws on every rank if it threw on any: an
// parameters::InputError stays one, any other error becomes an AgreedFailure.
void agree(const Teuchos::Comm<int>& comm, const std::function<void()>& check, bool on_root_only = false);

// Ends the whole MPI job with `exit_code` (MPI_Abort); on one rank, a plain exit.
[[noreturn]] void abort_all(int exit_code);
// Ends this process at once with `exit_code`, its standard streams flushed, without MPI_Finalize and the library
// shutdowns it runs: for a process whose HDF5 library holds a file it could not close (io::Hdf5File::unclosed_files),
// which HDF5's shutdown would crash on.
[[noreturn]] void end_now(int exit_code);

}  // namespace spatula::app
