#include "io/run_lock.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace spatula::io {

namespace {

constexpr const char* signature = "spatula run lock: process ";

std::string reason() { return std::strerror(errno); }

// What the lock file says (the holder's process and host), or "" for an empty file.
std::string contents(int descriptor)
{
  char text[512] = {};
  const ssize_t count = ::pread(descriptor, text, sizeof text - 1, 0);
  if (count <= 0) return "";
  std::string line(text, static_cast<std::size_t>(count));
  return line.substr(0, line.find('\n'));
}

// Whether `descriptor` still is the file at `file` (a run that ended may have removed it between our open and our
// flock: the lock is then on a file nobody else can find).
bool still_there(int descriptor, const std::string& file)
{
  struct stat held {}, named {};
  return ::fstat(descriptor, &held) == 0 && ::stat(file.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
         held.st_ino == named.st_ino;
}

}  // namespace

std::string RunLock::file_of(const std::string& path)
{
  std::filesystem::path normal = std::filesystem::absolute(path).lexically_normal();
  if (normal.filename().empty() && normal.has_parent_path()) normal = normal.parent_path();
  return normal.string() + ".lock";
}

RunLock::RunLock(const std::string& path) : file_(file_of(path))
{
  for (;;) {
    descriptor_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (descriptor_ < 0) throw std::runtime_error("cannot create the lock file '" + file_ + "': " + reason());
    const std::string holder = contents(descriptor_);
    if (!holder.empty() && holder.rfind(signature, 0) != 0) {
      ::close(descriptor_);
      descriptor_ = -1;
      throw DirectoryInUse("'" + file_ + "' exists and was not written by spatula: it is never replaced (remove it "
                           "yourself or choose another directory)");
    }
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      // The holder writes its name just after taking the lock: a run started at the same moment waits for it (a
      // second at most, a busy machine's scheduling) so that the refusal can name it.
      std::string holder_now = holder;
      for (int wait = 0; error == EWOULDBLOCK && holder_now.empty() && wait < 40; ++wait) {
        ::usleep(25000);
        holder_now = contents(descriptor_);
      }
      ::close(descriptor_);
      descriptor_ = -1;
      if (error != EWOULDBLOCK)
        throw std::runtime_error("cannot lock '" + file_ + "': " + std::strerror(error));
      holder_now = holder_now.rfind(signature, 0) == 0 ? holder_now.substr(std::strlen("spatula run lock: "))
                                                        : std::string("another run");
      throw DirectoryInUse("'" + path + "' is being written by another run (" + holder_now + ", lock file '" + file_ +
                           "'): wait for it to end, or choose another 'Output/directory'");
    }
    if (still_there(descriptor_, file_)) break;
    ::close(descriptor_);   // removed by the run that ended: lock the file that is there now
  }
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string line = signature + std::to_string(::getpid()) + " on " + host + "\n";
  if (::ftruncate(descriptor_, 0) != 0 ||
      ::pwrite(descriptor_, line.data(), line.size(), 0) != static_cast<ssize_t>(line.size())) {
    const std::string why = reason();
    ::unlink(file_.c_str());
    ::close(descriptor_);
    descriptor_ = -1;
    throw std::runtime_error("cannot write the lock file '" + file_ + "': " + why);
  }
}

RunLock::~RunLock()
{
  if (descriptor_ < 0) return;
  ::unlink(file_.c_str());   // while still held: a run waiting for it then finds it gone and makes its own
  ::close(descriptor_);
}

}  // namespace spatula::io
