#include "output_directory.hpp"

#include <filesystem>
#include <stdexcept>

namespace spatula::io {

namespace fs = std::filesystem;

OutputDirectory::OutputDirectory(std::string path) : path_(std::move(path)), staging_(path_ + ".partial")
{
  std::error_code error;
  fs::remove_all(staging_, error);
  if (!fs::create_directories(staging_, error) || error)
    throw std::runtime_error("cannot create output directory '" + staging_ + "': " + error.message());
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
  fs::remove_all(path_);
  fs::rename(staging_, path_);
  open_ = false;
}

void OutputDirectory::abandon()
{
  const std::string incomplete = path_ + ".incomplete";
  fs::remove_all(incomplete);
  fs::rename(staging_, incomplete);
  open_ = false;
}

}  // namespace spatula::io
