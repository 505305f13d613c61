#pragma once
// The limits a shell (ulimit), a batch system (Slurm's cgroups, its --mem) or a container can put on a job, read
// before a run so that the preflight refuses a run that cannot fit, naming the limit and where it comes from.
#include <string>
#include <vector>

namespace spatula::app {

// Memory the run may still take from one source, for all its ranks together (a per-process limit holds for each
// rank alone: its headroom times the rank count).
struct MemoryLimit {
  double bytes = 0.0;
  std::string source;   // for messages: "MemAvailable of this machine", "the address-space limit (ulimit -v) ..."
  std::string remedy;   // how a user raises it
};

// Every memory limit that applies to this process: the machine's MemAvailable, the memory control group's limit less
// its use (cgroup v2 memory.max, v1 memory.limit_in_bytes, the tightest of the group and its ancestors), and the
// address-space and data-segment limits (RLIMIT_AS, RLIMIT_DATA) less what this process maps already and what the
// libraries map once the solve starts.
std::vector<MemoryLimit> memory_limits(int ranks);
// The smallest of them (infinite bytes and no source where none is known).
MemoryLimit tightest(const std::vector<MemoryLimit>& limits);

// What a rank maps apart from the run's own data (libraries, MPI, thread stacks and arenas, the BLAS buffers), kept
// free under a per-process limit: the peak VmSize of a one-rank rotation less the memory estimate was 0.70 GB on the
// coarse mesh and 0.74 GB on the medium (VmData: 0.34 and 0.38 GB). Where the process maps more than usual already
// at the preflight, its VmSize then plus what the solve adds (0.18 and 0.22 GB measured) counts instead.
constexpr double process_address_space = 0.8e9, process_data = 0.45e9, added_by_solve = 0.25e9;

// A per-process limit on something other than memory (RLIMIT_FSIZE, RLIMIT_NOFILE): its soft value and its name.
struct ProcessLimit {
  double value = 0.0;   // infinite where unlimited
  std::string name;
};
ProcessLimit file_size_limit();    // bytes
ProcessLimit open_files_limit();   // descriptors

// Descriptors a run holds open at most (libraries, MPI's shared memory and sockets, HDF5, the curve, the lock),
// with room to spare: a medium rotation held at most 22 on one rank, 19 per rank on two.
constexpr int needed_open_files = 32;
// The file-size limit MPI needs to start (its shared-memory segments are files): Open MPI's start failed under a
// limit of 1 MB and passed at 5 MB.
constexpr double file_size_to_start = 8e6;
// Why this process cannot even start MPI under its limits (checked before MPI_Init, where MPI's own failure would
// not name the limit), or an empty string.
std::string limits_too_small_to_start();

}  // namespace spatula::app
