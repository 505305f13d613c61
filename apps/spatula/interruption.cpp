#include "interruption.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <csignal>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/time.h>
#include <unistd.h>

namespace spatula::app {

namespace {

constexpr int stop_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGXCPU};
constexpr int ignored_signals[] = {SIGPIPE, SIGXFSZ};

volatile std::sig_atomic_t first_signal = 0;
volatile std::sig_atomic_t checkpoint_written = 0;
volatile std::sig_atomic_t watchdog_ready = 0;   // the buffers below are filled in
double grace_seconds = 600.0;

// What the watchdog writes, prepared before a signal can need it (a handler may only call async-signal-safe
// functions: open, write, rename, _exit).
struct WatchdogOutput {
  char failure_file[4096] = {}, staging[4096] = {}, incomplete[4096] = {};
  char note[2048] = {}, without_checkpoint[512] = {}, with_checkpoint[512] = {};
} watchdog;

void copy(char* target, std::size_t size, const std::string& text)
{
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(target, text.data(), n);
  target[n] = '\0';
}

void write_text(int descriptor, const char* text) { (void)!::write(descriptor, text, std::strlen(text)); }

const char* name_of(int signal)
{
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGQUIT: return "SIGQUIT";
    case SIGUSR1: return "SIGUSR1";
    case SIGUSR2: return "SIGUSR2";
    case SIGXCPU: return "SIGXCPU";
    default: return "a signal";
  }
}

extern "C" void end_by_watchdog(int)
{
  const int signal = first_signal;
  write_text(2, "\nspatula: no converged state within 'Job/stop grace' of ");
  write_text(2, name_of(signal));
  write_text(2, ": the watchdog ends the run now\n");
  if (watchdog_ready) {
    const int note = ::open(watchdog.failure_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (note >= 0) {
      write_text(note, watchdog.note);
      write_text(note, checkpoint_written ? watchdog.with_checkpoint : watchdog.without_checkpoint);
      ::close(note);
    }
    if (::rename(watchdog.staging, watchdog.incomplete) == 0) {
      write_text(2, "spatula: results up to the last converged state and FAILURE.txt are in ");
      write_text(2, watchdog.incomplete);
      write_text(2, "/\n");
    }
    write_text(2, checkpoint_written ? watchdog.with_checkpoint : watchdog.without_checkpoint);
  }
  ::_exit(128 + signal);
}

// One SIGALRM after the grace (setitimer: a system call, safe in a handler on Linux).
void start_watchdog()
{
  itimerval timer{};
  timer.it_value.tv_sec = static_cast<time_t>(grace_seconds);
  timer.it_value.tv_usec = static_cast<suseconds_t>(1e6 * (grace_seconds - double(timer.it_value.tv_sec)));
  if (timer.it_value.tv_sec == 0 && timer.it_value.tv_usec == 0) timer.it_value.tv_usec = 1;
  ::setitimer(ITIMER_REAL, &timer, nullptr);
}

extern "C" void record_signal(int signal)
{
  if (first_signal == 0) {
    first_signal = signal;
    if (grace_seconds > 0.0) start_watchdog();
  }
  // A second SIGINT, SIGTERM or SIGQUIT (a user or a batch system insisting) ends the process at once; the others
  // repeat by themselves (the kernel sends SIGXCPU every second past the soft limit, a batch system may warn twice).
  if (signal == SIGINT || signal == SIGTERM || signal == SIGQUIT) std::signal(signal, SIG_DFL);
}

}  // namespace

void install_interruption_handlers()
{
  for (int signal : stop_signals) {
    struct sigaction inherited {};
    // A run started under nohup keeps SIGHUP ignored: closing the terminal is what nohup is for.
    if (signal == SIGHUP && ::sigaction(SIGHUP, nullptr, &inherited) == 0 && inherited.sa_handler == SIG_IGN) continue;
    std::signal(signal, record_signal);
  }
  for (int signal : ignored_signals) std::signal(signal, SIG_IGN);
  std::signal(SIGALRM, end_by_watchdog);
}

int received_signal() { return first_signal; }

std::string signal_name(int signal) { return name_of(signal); }

void set_stop_grace(double seconds) { grace_seconds = std::max(0.0, seconds); }

void set_watchdog_output(const std::string& failure_file, const std::string& staging, const std::string& incomplete,
                         const std::string& note)
{
  watchdog_ready = 0;
  copy(watchdog.failure_file, sizeof watchdog.failure_file, failure_file);
  copy(watchdog.staging, sizeof watchdog.staging, staging);
  copy(watchdog.incomplete, sizeof watchdog.incomplete, incomplete);
  copy(watchdog.note, sizeof watchdog.note, note);
  copy(watchdog.with_checkpoint, sizeof watchdog.with_checkpoint,
       "the last checkpoint ('last state' in checkpoints.h5) is kept: 'spatula <the scene> --resume' goes on from it\n");
  copy(watchdog.without_checkpoint, sizeof watchdog.without_checkpoint,
       "no checkpoint had been written yet ('Output/checkpoint interval'): run the scene again\n");
  watchdog_ready = 1;
}

void note_checkpoint_written() { checkpoint_written = 1; }

void cancel_watchdog()
{
  const itimerval off{};
  ::setitimer(ITIMER_REAL, &off, nullptr);
}

namespace {

// Where a stop signal usually comes from, for the log and FAILURE.txt.
const char* sender_of(int signal)
{
  switch (signal) {
    case SIGHUP: return " (the terminal closed)";
    case SIGUSR1:
    case SIGUSR2: return " (a batch system's warning before its time limit, or a user)";
    case SIGXCPU: return " (the CPU-time limit, ulimit -t, was reached)";
    default: return "";
  }
}

}  // namespace

Interrupted::Interrupted(int signal)
    : std::runtime_error("interrupted by " + signal_name(signal) + sender_of(signal)), signal(signal)
{
}

void stop_if_interrupted(const Teuchos::Comm<int>& comm)
{
  int local = received_signal(), global = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, local, Teuchos::outArg(global));
  if (global != 0) throw Interrupted(global);
}

}  // namespace spatula::app
