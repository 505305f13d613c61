#pragma once
// A run's output directory, written atomically and never at the expense of anything the program did not write.
//
// Files go to a staging directory "<path>.partial"; `commit` renames it to <path>, `abandon` to
// "<path>.incomplete" (a run that stops with an error never leaves a directory that looks complete). Every
// directory made here carries a marker file (`marker_name`), and only a directory with that marker is ever removed
// or replaced: an earlier result of this program, not a user's folder. `refusal` tells, before anything is
// computed or written, why a path cannot be used (the working directory or one of its ancestors, the home
// directory, an existing file or foreign directory, a name too long, a place where nothing can be created).
// Only the rank that writes (rank 0) creates one.
#include <optional>
#include <string>
#include <vector>

namespace spatula::io {

class OutputDirectory {
public:
  static constexpr const char* marker_name = ".spatula-output";

  // Why `path` cannot be this run's output directory, or nothing if it can. With `replace_earlier` an earlier
  // result of this program at `path` is replaced at the end of the run; without, any existing `path` is refused.
  // Looks only: creates nothing.
  static std::optional<std::string> refusal(const std::string& path, bool replace_earlier);
  // Whether `file` lies inside `path`, its staging or its incomplete directory (which a run replaces).
  static bool would_replace(const std::string& path, const std::string& file);

  explicit OutputDirectory(const std::string& path);   // creates the staging directory; throws if it cannot
  // Goes on with a stopped run: `stopped` (one of `stopped_runs(path)`) becomes the staging directory again, with
  // everything in it kept.
  OutputDirectory(const std::string& path, const std::string& stopped);
  // The directories a stopped run of this program left for `path`, newest kind first: the staging directory (the
  // run was killed) and the incomplete one (it stopped on a signal or an error).
  static std::vector<std::string> stopped_runs(const std::string& path);
  // Whether `directory` is a directory this program wrote (it has the marker).
  static bool is_ours(const std::string& directory);
  // The staging directory of `path` ("<path>.partial", absolute).
  static std::string staging_path(const std::string& path);
  ~OutputDirectory();                                  // abandons if neither committed nor abandoned
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Path of a file inside the staging directory.
  std::string file(const std::string& name) const;
  const std::string& final_path() const { return path_; }
  const std::string& incomplete_path() const { return incomplete_; }
  void commit();
  void abandon();

private:
  std::string path_, staging_, incomplete_;
  bool open_ = true;
};

}  // namespace spatula::io
