#include "command_line.hpp"

#include "spatula_version.hpp"   // generated at build time: the version and the source's commit

#include <Kokkos_Core.hpp>
#include <Trilinos_version.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace spatula::app {

const char* usage()
{
  return "usage: spatula [options] [scene.xml]\n"
         "Runs the scene (a Teuchos XML parameter list), or without one the embedded default scene (xml/default.xml).\n"
         "options:\n"
         "  --resume            go on with the stopped run of this scene (killed, interrupted or failed) from the last\n"
         "                      state it checkpointed (Output/checkpoint interval), in the same Output/directory\n"
         "  --stop-after-checkpoint THETA\n"
         "                      stop once the rotation has written its checkpoint at THETA deg (one of\n"
         "                      'Loading/checkpoints at theta_y'), exit 0: the run is left stopped there (a workflow\n"
         "                      job that hands a pull-off its start), to be resumed later\n"
         "  --validate-only     check the scene, the mesh's memory and the output directory, and exit\n"
         "  --print-parameters  print every valid key with its default and documentation\n"
         "  --version           print the version, the commit and the Trilinos and Kokkos it runs on\n"
         "  -h, --help          print this usage\n"
         "  --kokkos-help       print Kokkos' own options (--kokkos-threads=N, ...), which the program passes on\n";
}

CommandLine parse_command_line(int argc, const char* const* argv)
{
  CommandLine line;
  line.kokkos_arguments.push_back(argc > 0 ? argv[0] : "spatula");
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--resume") line.resume = true;
    else if (argument == "--stop-after-checkpoint" || argument.rfind("--stop-after-checkpoint=", 0) == 0) {
      const bool attached = argument.size() > std::string("--stop-after-checkpoint").size();
      const std::string value = attached ? argument.substr(argument.find('=') + 1) : i + 1 < argc ? argv[++i] : "";
      char* end = nullptr;
      const double theta = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !std::isfinite(theta)) {
        if (line.error.empty())
          line.error = "--stop-after-checkpoint needs an inclination in degrees (one of the scene's 'Loading/"
                       "checkpoints at theta_y'), got '" + value + "'";
      } else {
        line.stop_after_checkpoint = theta;
      }
    }
    else if (argument == "--validate-only") line.validate_only = true;
    else if (argument == "--print-parameters") line.print_parameters = true;
    else if (argument == "--version") line.version = true;
    else if (argument == "--help" || argument == "-h") line.help = true;
    else if (argument.rfind("--kokkos-", 0) == 0) {
      line.kokkos_arguments.push_back(argument);
      if (argument == "--kokkos-help") line.kokkos_help = true;
    } else if (!argument.empty() && argument[0] == '-') {
      if (line.error.empty()) line.error = "unknown option '" + argument + "'";
    } else if (line.scene_file.empty()) {
      line.scene_file = argument;
    } else if (line.error.empty()) {
      line.error = "more than one scene file given ('" + line.scene_file + "', '" + argument + "')";
    }
  }
  return line;
}

std::string version_text()
{
  using Space = Kokkos::DefaultExecutionSpace;
  std::ostringstream text;
  text << "spatula " << version::number << " (commit " << version::commit << ")\n"
       << "Trilinos " << TRILINOS_VERSION_STRING << ", Kokkos " << KOKKOS_VERSION / 10000 << "."
       << KOKKOS_VERSION / 100 % 100 << "." << KOKKOS_VERSION % 100 << ": " << Space::name() << " backend, "
       << Space().concurrency() << " thread(s)\n";
  return text.str();
}

KokkosArguments::KokkosArguments(const std::vector<std::string>& arguments) : storage_(arguments)
{
  for (auto& argument : storage_) pointers_.push_back(argument.data());
  pointers_.push_back(nullptr);
  argc = static_cast<int>(storage_.size());
  argv = pointers_.data();
}

}  // namespace spatula::app
