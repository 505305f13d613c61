#include "io/checked_write.hpp"

#include <cerrno>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace spatula::io {

std::string write_failure(const std::string& file)
{
  return "cannot write '" + file + "': " + (errno != 0 ? std::strerror(errno) : "the write failed");
}

void write_text_file(const std::string& file, const std::string& text, bool append)
{
  errno = 0;
  std::ofstream out(file, append ? std::ios::app : std::ios::trunc);
  if (!out) throw std::runtime_error(write_failure(file));
  out << text;
  out.close();   // the data reach the file system here: a full disk shows on the flush
  if (!out) throw std::runtime_error(write_failure(file));
}

void check_written(std::ostream& stream, const std::string& file)
{
  errno = 0;
  stream.flush();
  if (!stream) throw std::runtime_error(write_failure(file));
}

void rename_path(const std::string& from, const std::string& to)
{
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + from + "' to '" + to + "': " + std::strerror(errno));
}

}  // namespace spatula::io
