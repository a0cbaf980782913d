// Process resource figures for benchmarks and stage reports.
#pragma once

#include <cstddef>

namespace carbtf {

// The process's peak resident set size so far, in bytes (getrusage), or 0 where unavailable.
std::size_t peak_rss_bytes();

}  // namespace carbtf
