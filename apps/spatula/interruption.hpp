#pragma once
// Signals that end or warn a job stop a run at its next converged state, cleanly: SIGINT and SIGQUIT (a terminal's
// keys), SIGHUP (the terminal closed), SIGTERM (kill, a batch system's end of a job), SIGUSR1 and SIGUSR2 (the
// warnings Slurm's --signal, LSF and Grid Engine send ahead of a time limit), SIGXCPU (the soft CPU-time limit). The
// handler only records the signal; the load path asks, collectively after every converged state, whether any rank
// has received one, and then every rank stops together (the state is checkpointed, the partial results kept). A
// second SIGINT, SIGTERM or SIGQUIT ends the process at once; under nohup SIGHUP stays ignored. SIGPIPE and SIGXFSZ are ignored: a write to a closed pipe or past the
// file-size limit fails like any other refused write (named, exit 1) instead of killing the process.
//
// A watchdog bounds the wait: where no converged state comes within the stop grace of the first signal (a solve that
// does not return), the process ends by itself (exit 128 + the signal), its output directory renamed
// <directory>.incomplete with FAILURE.txt saying so, the last checkpoint kept.
#include <Teuchos_Comm.hpp>

#include <stdexcept>
#include <string>

namespace spatula::app {

void install_interruption_handlers();
int received_signal();   // the first stop signal received by this rank, 0 if none
std::string signal_name(int signal);   // "SIGTERM"

// The watchdog's grace in seconds (0: none), and what it leaves behind on rank 0 once the output directory exists:
// FAILURE.txt at `failure_file` with `note`, the staging directory renamed from `staging` to `incomplete`.
void set_stop_grace(double seconds);
void set_watchdog_output(const std::string& failure_file, const std::string& staging, const std::string& incomplete,
                         const std::string& note);
// A checkpoint to go on from now exists (the watchdog's note says so).
void note_checkpoint_written();
// The run has reached the converged state it stops at: the watchdog is no longer needed.
void cancel_watchdog();

// Thrown on every rank at a converged state once any rank has received a signal.
class Interrupted : public std::runtime_error {
public:
  explicit Interrupted(int signal);
  int signal;
};

// Collective: throws Interrupted on every rank if any rank has received a signal.
void stop_if_interrupted(const Teuchos::Comm<int>& comm);

}  // namespace spatula::app
