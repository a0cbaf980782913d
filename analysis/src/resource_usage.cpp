#include "carbtf/analysis/resource_usage.hpp"

#include <sys/resource.h>

namespace carbtf {

std::size_t peak_rss_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace carbtf
