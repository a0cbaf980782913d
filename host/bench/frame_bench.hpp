// What `carbtf bench frame` records per frame and the report it writes from them. Nothing here asserts
// a timing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace carbtf::cli {

struct FrameRecord {
  std::uint32_t frame = 0;
  std::size_t synthesized = 0;  // subspace images synthesized on this frame (0: none)
  std::size_t resident = 0;     // subspace images available to the render
  double synthesis_gpu_ms = 0.0;
  double render_gpu_ms = 0.0;
  double wall_ms = 0.0;
};

// Writes OUT/bench_frame.csv (one row per frame) and OUT/bench_frame.md (`heading`, then a table of
// median and 95th-percentile times: render pass and synthesis GPU timestamps, frame wall times with and
// without synthesis); returns the table.
std::string write_frame_bench_report(const std::filesystem::path& out,
                                     const std::vector<FrameRecord>& records, const std::string& heading);

// `bench frame --parts`: the render pass with one part of the fragment stage replaced by a constant
// (MaterialBindingInfo::cost_probe), or drawn with the other pair coupling, its frames rendered in turn
// with the full pass's.
struct FramePartTimes {
  std::string part;                   // "none" for the full pass
  std::vector<double> render_gpu_ms;  // one per frame
};

// Writes OUT/bench_frame_parts.csv (part, frame, render pass ms) and OUT/bench_frame_parts.md
// (`heading`, then per part the median render pass without it and the difference to the full pass's
// median: what the part costs); returns the table. parts[0] is the full pass.
std::string write_frame_parts_report(const std::filesystem::path& out,
                                     const std::vector<FramePartTimes>& parts, const std::string& heading);

}  // namespace carbtf::cli
