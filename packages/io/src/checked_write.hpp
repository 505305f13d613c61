#pragma once
// Writes whose failure is never silent: each throws std::runtime_error naming the file and the system's reason
// ("No space left on device", "Permission denied"), so that a full disk or a removed directory ends the run with a
// message instead of a truncated result.
#include <ostream>
#include <string>

namespace spatula::io {

// Writes `text` to `file` whole (replacing it, or appended with `append`), flushed and closed.
void write_text_file(const std::string& file, const std::string& text, bool append = false);
// Flushes `stream` (an open file named `file`) and throws if any write to it failed.
void check_written(std::ostream& stream, const std::string& file);
// Renames `from` to `to`.
void rename_path(const std::string& from, const std::string& to);
// The message of a failed write of `file`, with errno's reason.
std::string write_failure(const std::string& file);

}  // namespace spatula::io
