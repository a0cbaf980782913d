// The material file's window filter (format 1.5) finds where equally sized rasters are windows of one
// smaller source raster, so that texels they share are stored once. The analysis cuts its range-map
// patches (heights and tone) from one map, often overlapping: four random 128^2 windows of a 256^2
// map share about 40% of their texels, which deflate cannot see beyond its 32 KiB window.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace carbtf::detail {

struct RasterWindows {
  std::uint32_t source_width = 0, source_height = 0;
  std::vector<std::uint32_t> cols, rows;  // per raster: the source texel of its top-left corner
  std::uint64_t source_texels() const { return std::uint64_t{source_width} * source_height; }
};

// A placement of `count` rasters (row-major, width x height values each, one after another in `values`)
// as windows of a source in which every texel that several windows cover holds one value in all of
// them, or nullopt when none found is smaller than the rasters side by side. Each raster goes where it
// shares the most texels with those placed before it (a greedy search, bounded in work so that no
// input makes it slow; the bound makes it give up, never err). Deterministic.
std::optional<RasterWindows> find_raster_windows(const std::vector<std::uint32_t>& values,
                                                 std::uint32_t width, std::uint32_t height,
                                                 std::uint32_t count);

// The source raster of a placement: each texel a window covers holds that window's value; the rest
// hold the raster filter's prediction (raster_prediction.hpp), so they cost nearly nothing.
std::vector<std::uint32_t> compose_window_source(const std::vector<std::uint32_t>& values,
                                                 std::uint32_t width, std::uint32_t height,
                                                 const RasterWindows& windows);

}  // namespace carbtf::detail
