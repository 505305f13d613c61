#include "resource_limits.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <sys/resource.h>

namespace spatula::app {

namespace {

namespace fs = std::filesystem;
constexpr double unlimited = std::numeric_limits<double>::infinity();

// A "key: value kB" line of a /proc file, in bytes (0 where missing).
double proc_bytes(const char* file, const std::string& wanted)
{
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string key;
    double kilobytes = 0.0;
    if (fields >> key >> kilobytes && key == wanted) return kilobytes * 1024.0;
  }
  return 0.0;
}

// A number from a cgroup file ("max" and the v1 "no limit" value read as unlimited; missing: unlimited).
double cgroup_number(const fs::path& file)
{
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text == "max") return unlimited;
  try {
    const double value = std::stod(text);
    return value >= 0.9 * double(std::numeric_limits<std::int64_t>::max()) ? unlimited : value;
  } catch (const std::exception&) {
    return unlimited;
  }
}

// The directories of this process' memory control group and of its ancestors, with the names of their limit and
// usage files: from /proc/self/cgroup (the group's path in each hierarchy) and /proc/self/mountinfo (where the
// hierarchy is mounted, and which of its paths the mount shows).
struct CgroupFiles {
  fs::path directory;
  const char* limit;
  const char* usage;
};

std::vector<CgroupFiles> memory_cgroups()
{
  std::vector<std::string> own;   // this process' groups, one line per hierarchy
  std::ifstream cgroup("/proc/self/cgroup");
  for (std::string entry; std::getline(cgroup, entry);) own.push_back(entry);
  std::vector<CgroupFiles> groups;
  std::ifstream mountinfo("/proc/self/mountinfo");
  for (std::string line; std::getline(mountinfo, line);) {
    std::istringstream fields(line);
    std::string id, parent, device, root, mount_point, field;
    fields >> id >> parent >> device >> root >> mount_point;
    while (fields >> field && field != "-") {
    }
    std::string type, source, options;
    fields >> type >> source >> options;
    const bool v2 = type == "cgroup2";
    const bool v1 = type == "cgroup" && ("," + options + ",").find(",memory,") != std::string::npos;
    if (!v1 && !v2) continue;
    for (const auto& entry : own) {
      const auto first = entry.find(':'), second = entry.find(':', first + 1);
      if (first == std::string::npos || second == std::string::npos) continue;
      const std::string controllers = entry.substr(first + 1, second - first - 1);
      const bool matches = v2 ? entry.compare(0, first, "0") == 0 && controllers.empty()
                              : ("," + controllers + ",").find(",memory,") != std::string::npos;
      if (!matches) continue;
      std::string path = entry.substr(second + 1);
      if (root != "/" && path.compare(0, root.size(), root) == 0) path = path.substr(root.size());
      for (fs::path directory = fs::path(mount_point) / fs::path(path).relative_path();;
           directory = directory.parent_path()) {
        groups.push_back({directory, v2 ? "memory.max" : "memory.limit_in_bytes",
                          v2 ? "memory.current" : "memory.usage_in_bytes"});
        if (directory == fs::path(mount_point) || directory == directory.parent_path()) break;
      }
    }
  }
  return groups;
}

std::string gigabytes(double bytes)
{
  std::ostringstream text;
  text.precision(3);
  text << bytes / 1e9 << " GB";
  return text.str();
}

double soft_limit(int resource)
{
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return unlimited;
  return double(limit.rlim_cur);
}

}  // namespace

std::vector<MemoryLimit> memory_limits(int ranks)
{
  std::vector<MemoryLimit> limits;
  if (const double available = proc_bytes("/proc/meminfo", "MemAvailable:"); available > 0.0)
    limits.push_back({available, "MemAvailable of this machine", "free memory on this machine, or run on a larger one"});
  for (const auto& group : memory_cgroups()) {
    const double limit = cgroup_number(group.directory / group.limit);
    if (!std::isfinite(limit)) continue;
    const double used = std::min(limit, cgroup_number(group.directory / group.usage));
    limits.push_back({limit - (std::isfinite(used) ? used : 0.0),
                      "the memory limit of the control group " + group.directory.string() + " (" + gigabytes(limit) +
                          ", " + group.limit + ") less its use",
                      "ask the batch system or container for more memory (Slurm: --mem)"});
  }
  const struct {
    int resource;
    const char* name;
    const char* in_use;   // what of it the process holds already (/proc/self/status)
    const char* remedy;
    double process;   // what a rank maps apart from the run's data
  } per_process[] = {
      {RLIMIT_AS, "the address-space limit (ulimit -v, RLIMIT_AS)", "VmSize:", "ulimit -v unlimited", process_address_space},
      {RLIMIT_DATA, "the data-segment limit (ulimit -d, RLIMIT_DATA)", "VmData:", "ulimit -d unlimited", process_data}};
  for (const auto& process : per_process) {
    const double limit = soft_limit(process.resource);
    if (!std::isfinite(limit)) continue;
    const double mapped = std::max(process.process, proc_bytes("/proc/self/status", process.in_use) + added_by_solve);
    const double headroom = limit - mapped;
    limits.push_back({std::max(0.0, headroom) * ranks,
                      std::string(process.name) + " of " + gigabytes(limit) + " per rank, less the " +
                          gigabytes(mapped) + " a rank maps apart from the run's data" + (ranks > 1 ? ", times " + std::to_string(ranks) + " ranks" : ""),
                      std::string("raise it: ") + process.remedy});
  }
  return limits;
}

MemoryLimit tightest(const std::vector<MemoryLimit>& limits)
{
  if (limits.empty()) return {unlimited, "", ""};
  return *std::min_element(limits.begin(), limits.end(),
                           [](const MemoryLimit& a, const MemoryLimit& b) { return a.bytes < b.bytes; });
}

ProcessLimit file_size_limit() { return {soft_limit(RLIMIT_FSIZE), "the file-size limit (ulimit -f, RLIMIT_FSIZE)"}; }

ProcessLimit open_files_limit() { return {soft_limit(RLIMIT_NOFILE), "the open-files limit (ulimit -n, RLIMIT_NOFILE)"}; }

std::string limits_too_small_to_start()
{
  const auto open_files = open_files_limit();
  if (open_files.value < needed_open_files)
    return open_files.name + " is " + std::to_string(int(open_files.value)) + ", but a run opens up to " +
           std::to_string(needed_open_files) + " files (libraries, MPI, HDF5, its outputs): raise it (ulimit -n " +
           std::to_string(needed_open_files) + ")";
  const auto file_size = file_size_limit();
  if (file_size.value < file_size_to_start)
    return file_size.name + " is " + std::to_string(int(file_size.value / 1024)) + " kB, but MPI needs " +
           std::to_string(int(file_size_to_start / 1e6)) + " MB to start (its shared memory is in files): raise it "
           "(ulimit -f unlimited)";
  return {};
}

}  // namespace spatula::app
