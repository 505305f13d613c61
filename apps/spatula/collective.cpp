#include "collective.hpp"

#include "parameters/parameter_validation.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <mpi.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace spatula::app {

void agree(const Teuchos::Comm<int>& comm, const std::function<void()>& check, bool on_root_only)
{
  enum Outcome : int { passed = 0, failed = 1, bad_input = 2 };
  int outcome = passed;
  std::string message;
  if (!on_root_only || comm.getRank() == 0) {
    try {
      check();
    } catch (const parameters::InputError& error) {
      outcome = bad_input;
      message = error.what();
    } catch (const std::exception& error) {
      outcome = failed;
      message = error.what();
    }
  }
  int worst = passed;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, outcome, Teuchos::outArg(worst));
  if (worst == passed) return;
  // The message of the lowest rank with the worst outcome, sent to all.
  int sender = outcome == worst ? comm.getRank() : comm.getSize();
  int first = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, sender, Teuchos::outArg(first));
  int length = static_cast<int>(message.size());
  Teuchos::broadcast(comm, first, Teuchos::outArg(length));
  std::vector<char> text(message.begin(), message.end());
  text.resize(length);
  if (length > 0) Teuchos::broadcast(comm, first, length, text.data());
  message.assign(text.begin(), text.end());
  if (worst == bad_input) throw parameters::InputError(message);
  throw AgreedFailure(message);
}

void abort_all(int exit_code)
{
  int initialized = 0, finalized = 0, size = 1;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (initialized && !finalized) MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::exit(exit_code);
}

void end_now(int exit_code)
{
  std::cout.flush();
  std::cerr.flush();
  std::_Exit(exit_code);
}

}  // namespace spatula::app
