#include "io/output_directory.hpp"

#include "io/checked_write.hpp"

#include <cstdlib>
#include <fstream>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace spatula::io {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t longest_name = 255, longest_path = 4000;   // NAME_MAX and (less than) PATH_MAX on Linux

// The absolute, normalized form of a path, without a trailing separator ("out/" and "out" are one directory).
fs::path absolute_path(const std::string& path)
{
  fs::path normal = fs::absolute(path).lexically_normal();
  if (normal.filename().empty() && normal.has_parent_path()) normal = normal.parent_path();
  return normal;
}

// Whether `inner` is `outer` or lies below it (both canonical).
bool inside(const fs::path& inner, const fs::path& outer)
{
  auto a = inner.begin(), b = outer.begin();
  for (; b != outer.end(); ++a, ++b)
    if (a == inner.end() || *a != *b) return false;
  return true;
}

bool ours(const fs::path& directory)
{
  std::error_code error;
  return fs::is_directory(directory, error) && fs::is_regular_file(directory / OutputDirectory::marker_name, error);
}

// The result itself and the staging, incomplete and set-aside names beside it: all a run may create and remove.
constexpr const char* run_suffixes[] = {"", ".partial", ".incomplete", ".previous"};
fs::path sibling(const fs::path& path, const char* suffix) { return fs::path(path.string() + suffix); }

void make_ours(const fs::path& directory)
{
  std::error_code error;
  fs::create_directories(directory, error);
  if (error || !fs::is_directory(directory))
    throw std::runtime_error("cannot create output directory '" + directory.string() + "': " + error.message());
  write_text_file((directory / OutputDirectory::marker_name).string(),
                  "Written by spatula. A later run with this Output/directory may replace this directory.\n");
}

// Removes a directory of ours; anything else is left alone.
void remove_ours(const fs::path& directory)
{
  if (!ours(directory)) throw std::runtime_error("refusing to remove '" + directory.string() + "': not written by spatula");
  fs::remove_all(directory);
}

// Whether a directory could be created at `path`: its nearest existing ancestor is a directory in which one can
// be made (tried with a probe that is removed at once).
std::optional<std::string> not_creatable(const fs::path& path)
{
  std::error_code error;
  fs::path ancestor = path.parent_path();
  while (!ancestor.empty() && !fs::exists(ancestor, error)) ancestor = ancestor.parent_path();
  if (!fs::is_directory(ancestor, error)) return "'" + ancestor.string() + "' is not a directory";
  const fs::path probe = ancestor / (".spatula-probe-" + std::to_string(::getpid()));
  if (!fs::create_directory(probe, error) || error)
    return "nothing can be created in '" + ancestor.string() + "' (" + error.message() + ")";
  fs::remove(probe, error);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> OutputDirectory::refusal(const std::string& path, bool replace_earlier)
{
  if (path.empty()) return "it is empty";
  if (path.size() > longest_path) return "the path is too long (" + std::to_string(path.size()) + " characters)";
  for (const auto& part : fs::path(path))
    if (part.string().size() > longest_name)
      return "a name in it is too long (" + std::to_string(part.string().size()) + " characters, at most " +
             std::to_string(longest_name) + ")";
  std::error_code error;
  const fs::path target = absolute_path(path);
  const fs::path real = fs::weakly_canonical(target, error);
  const fs::path working = fs::canonical(fs::current_path(), error);
  if (real == working) return "it is the working directory (the run would replace it)";
  if (inside(working, real)) return "it contains the working directory '" + working.string() + "'";
  if (const char* home = std::getenv("HOME")) {
    const fs::path home_path = fs::weakly_canonical(home, error);
    if (!error && inside(home_path, real)) return "it is the home directory or contains it";
  }
  if (fs::is_symlink(target, error)) return "it is a symbolic link (give the directory itself)";
  for (const char* suffix : run_suffixes) {
    const fs::path candidate = sibling(target, suffix);
    if (!fs::exists(fs::symlink_status(candidate, error))) continue;
    const std::string name = "'" + candidate.string() + "'";
    if (!fs::is_directory(fs::symlink_status(candidate, error)))
      return name + " exists and is not a directory: it is never replaced (choose another directory)";
    if (!ours(candidate))
      return name + " exists and was not written by spatula (it has no " + std::string(marker_name) +
             "): it is never replaced (remove it yourself or choose another directory)";
    if (*suffix == '\0' && !replace_earlier)
      return name + " holds an earlier result and 'Output/overwrite' is false";
  }
  return not_creatable(target);
}

bool OutputDirectory::would_replace(const std::string& path, const std::string& file)
{
  std::error_code error;
  const fs::path target = absolute_path(path);
  const fs::path real_file = fs::weakly_canonical(absolute_path(file), error);
  for (const char* suffix : run_suffixes)
    if (inside(real_file, fs::weakly_canonical(sibling(target, suffix), error))) return true;
  return false;
}

OutputDirectory::OutputDirectory(const std::string& path)
    : path_(absolute_path(path).string()), staging_(path_ + ".partial"), incomplete_(path_ + ".incomplete")
{
  if (const auto why = refusal(path, true)) throw std::runtime_error("output directory '" + path + "': " + *why);
  if (fs::exists(staging_)) remove_ours(staging_);   // a run stopped by kill -9 left it
  make_ours(staging_);
}

OutputDirectory::OutputDirectory(const std::string& path, const std::string& stopped)
    : path_(absolute_path(path).string()), staging_(path_ + ".partial"), incomplete_(path_ + ".incomplete")
{
  const fs::path from = absolute_path(stopped);
  if ((from != fs::path(staging_) && from != fs::path(incomplete_)) || !ours(from))
    throw std::runtime_error("'" + stopped + "' is not a stopped run of output directory '" + path + "'");
  if (from != fs::path(staging_)) {
    if (fs::exists(staging_)) remove_ours(staging_);
    fs::rename(from, staging_);
  }
}

bool OutputDirectory::is_ours(const std::string& directory) { return ours(directory); }

std::string OutputDirectory::staging_path(const std::string& path) { return absolute_path(path).string() + ".partial"; }

std::vector<std::string> OutputDirectory::stopped_runs(const std::string& path)
{
  std::vector<std::string> found;
  for (const char* suffix : {".partial", ".incomplete"}) {
    const fs::path candidate = sibling(absolute_path(path), suffix);
    if (ours(candidate)) found.push_back(candidate.string());
  }
  return found;
}

OutputDirectory::~OutputDirectory()
{
  if (open_) {
    try {
      abandon();
    } catch (...) {
    }
  }
}

std::string OutputDirectory::file(const std::string& name) const { return (fs::path(staging_) / name).string(); }

void OutputDirectory::commit()
{
  // The earlier result is set aside, the new one takes its name, then the earlier one goes: at every moment
  // <path> is either the whole earlier result or the whole new one.
  const fs::path previous = path_ + ".previous";
  if (fs::exists(previous)) remove_ours(previous);
  if (fs::exists(path_)) {
    if (!ours(path_)) throw std::runtime_error("refusing to replace '" + path_ + "': not written by spatula");
    fs::rename(path_, previous);
  }
  fs::rename(staging_, path_);
  open_ = false;
  if (fs::exists(previous)) remove_ours(previous);
  if (fs::exists(incomplete_)) remove_ours(incomplete_);   // an earlier failed attempt is superseded
}

void OutputDirectory::abandon()
{
  open_ = false;
  if (fs::exists(incomplete_)) remove_ours(incomplete_);
  fs::rename(staging_, incomplete_);
}

}  // namespace spatula::io
