#pragma once
// What the load path's files share: a monotonic clock for the log's seconds and the descent's cost rule, and the
// format of a load value in the log.
#include <chrono>
#include <cstdio>
#include <string>

namespace spatula::analysis {

inline double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A load value for the log, independent of the stream's current format.
inline std::string load_text(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  return text;
}

}  // namespace spatula::analysis
