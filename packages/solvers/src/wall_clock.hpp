#pragma once
// A monotonic clock in seconds, for logs, progress lines and the cost rules that decide by measured time.
#include <chrono>

namespace spatula::solvers {

inline double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace spatula::solvers
