// Process resource figures for benchmarks and stage reports.
#pragma once

#include <cstddef>

namespace carbtf {

// The process's peak resident set size so far, in bytes (getrusage), or 0 where unavailable.
std::size_t peak_rss_bytes();

// The resident set's high-water mark since the last reset_peak_rss() (Linux: VmHWM), or 0 where
// unavailable; and the reset (Linux: /proc/self/clear_refs), false where unavailable. For measuring one
// step's peak in a process that ran others before it (getrusage keeps the whole life's peak).
std::size_t resident_high_water_bytes();
bool reset_peak_rss();

}  // namespace carbtf
