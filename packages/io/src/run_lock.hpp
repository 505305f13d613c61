#pragma once
// The lock that makes one live run the owner of an output directory: "<directory>.lock" beside it, held with
// flock(2) from before anything is written until the run has renamed its directory for the last time. The kernel
// releases it when the process ends in any way, so the lock of a killed run never blocks the next one; its file
// is then taken over. A run that ends removes the file.
#include <stdexcept>
#include <string>

namespace spatula::io {

// The directory is being written by another live run (or its lock file is not one of ours).
class DirectoryInUse : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class RunLock {
public:
  // The lock file of output directory `path`.
  static std::string file_of(const std::string& path);
  // Takes the lock of `path` or throws DirectoryInUse naming the directory and the process that holds it. Other
  // failures (no file can be made there) throw std::runtime_error with the system's reason.
  explicit RunLock(const std::string& path);
  ~RunLock();   // removes the lock file and releases the lock
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

private:
  std::string file_;
  int descriptor_ = -1;
};

}  // namespace spatula::io
