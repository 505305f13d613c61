#pragma once
// What the load path's files share: the monotonic clock (solvers/wall_clock.hpp) and the format of a load value in
// the log.
#include "solvers/wall_clock.hpp"

#include <cstdio>
#include <string>

namespace spatula::analysis {

using solvers::now;

// A load value for the log, independent of the stream's current format.
inline std::string load_text(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  return text;
}

}  // namespace spatula::analysis
