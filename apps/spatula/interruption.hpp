#pragma once
// SIGINT and SIGTERM stop a run at its next converged state, cleanly: the handler only records the signal; the load
// path asks, collectively after every converged state, whether any rank has received one, and then every rank stops
// together (the state is checkpointed, the partial results kept). A second signal ends the process at once.
#include <Teuchos_Comm.hpp>

#include <stdexcept>

namespace spatula::app {

void install_interruption_handlers();
int received_signal();   // the first SIGINT/SIGTERM received by this rank, 0 if none

// Thrown on every rank at a converged state once any rank has received a signal.
class Interrupted : public std::runtime_error {
public:
  explicit Interrupted(int signal);
  int signal;
};

// Collective: throws Interrupted on every rank if any rank has received a signal.
void stop_if_interrupted(const Teuchos::Comm<int>& comm);

}  // namespace spatula::app
