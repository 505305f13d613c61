#include "interruption.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <csignal>
#include <string>

namespace spatula::app {

namespace {

volatile std::sig_atomic_t first_signal = 0;

extern "C" void record_signal(int signal)
{
  if (first_signal == 0) first_signal = signal;
  std::signal(signal, SIG_DFL);   // a second one ends the process
}

}  // namespace

void install_interruption_handlers()
{
  std::signal(SIGINT, record_signal);
  std::signal(SIGTERM, record_signal);
}

int received_signal() { return first_signal; }

Interrupted::Interrupted(int signal)
    : std::runtime_error(std::string("interrupted by ") + (signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal")),
      signal(signal)
{
}

void stop_if_interrupted(const Teuchos::Comm<int>& comm)
{
  int local = received_signal(), global = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, local, Teuchos::outArg(global));
  if (global != 0) throw Interrupted(global);
}

}  // namespace spatula::app
