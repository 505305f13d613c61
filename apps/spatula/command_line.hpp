// The program's command line: its own options, and those it hands to Kokkos.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace spatula::app {

struct CommandLine {
  std::string scene_file;   // empty: the embedded default scene
  bool resume = false;
  std::optional<double> stop_after_checkpoint;   // --stop-after-checkpoint THETA [deg]
  bool validate_only = false;
  bool print_parameters = false;
  bool help = false;
  bool version = false;
  bool kokkos_help = false;
  std::string error;                       // a malformed command line (the usage follows it)
  std::vector<std::string> kokkos_arguments;   // the program's name and every --kokkos-* option, for Kokkos::initialize
};

// Reads argv without throwing (the error is reported once MPI runs, on one rank). Options of the form --kokkos-*
// are Kokkos' (--kokkos-threads=N, ...); every other option is the program's.
CommandLine parse_command_line(int argc, const char* const* argv);

// The usage text: each option once.
const char* usage();

// "spatula <version> (commit <hash>)" and the libraries it runs on: Trilinos' version, Kokkos' version, backend and
// thread count (Kokkos must be initialized).
std::string version_text();

// argc/argv for Kokkos::initialize (it removes the options it recognizes from them).
class KokkosArguments {
 public:
  explicit KokkosArguments(const std::vector<std::string>& arguments);
  int argc;
  char** argv;

 private:
  std::vector<std::string> storage_;
  std::vector<char*> pointers_;
};

}  // namespace spatula::app
