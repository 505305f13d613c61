#include "solvers/out_of_memory.hpp"

#include <cstdio>

namespace spatula::solvers {

OutOfMemory::OutOfMemory(const std::string& what, double bytes, bool collective)
    : message_("out of memory: " + what + (bytes > 0.0 ? " (" + memory_size_text(bytes) + ")" : std::string())),
      collective_(collective)
{
}

std::string memory_size_text(double bytes)
{
  char text[32];
  if (bytes >= 1e9) std::snprintf(text, sizeof text, "%.2f GB", bytes / 1e9);
  else if (bytes >= 1e6) std::snprintf(text, sizeof text, "%.0f MB", bytes / 1e6);
  else std::snprintf(text, sizeof text, "%.1f kB", bytes / 1e3);
  return text;
}

}  // namespace spatula::solvers
