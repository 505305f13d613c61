#pragma once
// A run's output directory, written atomically: files go to a staging directory "<path>.partial" and `commit`
// renames it to <path> (replacing an older result). A run that stops with an error never leaves a directory that
// looks complete: `abandon` renames the staging directory to "<path>.incomplete" for diagnosis.
// Only the rank that writes (rank 0) creates one.
#include <string>

namespace spatula::io {

class OutputDirectory {
public:
  explicit OutputDirectory(std::string path);   // creates the staging directory; throws if it cannot
  ~OutputDirectory();                           // abandons if neither committed nor abandoned
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Path of a file inside the staging directory.
  std::string file(const std::string& name) const;
  const std::string& final_path() const { return path_; }
  void commit();
  void abandon();

private:
  std::string path_, staging_;
  bool open_ = true;
};

}  // namespace spatula::io
