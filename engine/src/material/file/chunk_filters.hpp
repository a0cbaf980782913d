// The filters a deflated chunk's payload goes through before zlib (format 1.1 and later), so that the
// rasters of heights, tone and pair gains deflate to little:
//   0         none;
//   1..8      Sub with that stride: each byte stored minus the byte `stride` before it, as PNG's Sub
//             filter, which turns smooth u16 and u8 rasters into small repeated values (no parameters);
//   9 (1.3)   raster: u32 skip, u8 value bytes (1 or 2, little-endian), u32 width, u32 height, u32
//             rasters, u8 rest stride. The payload's first `skip` bytes are stored as they are; the
//             `rasters` row-major rasters after them are stored as each value minus its prediction
//             (raster_prediction.hpp), modulo 2^(8 value bytes), zigzag-mapped (0, -1, 1, -2, ... to 0,
//             1, 2, 3, ...), low bytes of every value first, then high bytes; the bytes after the
//             rasters take the Sub filter of `rest stride` (0..8).
//   10 (1.5)  windows: the raster filter's parameters, then u32 source width, u32 source height, and
//             per raster u32 column, u32 row: each raster is the window of one source raster at that
//             texel (raster_windows.hpp), so texels several rasters share are stored once. The stream
//             holds the `skip` bytes, the source raster under the raster filter (one raster of the
//             source's size), then the bytes after the rasters under their Sub filter; the source has at
//             most the rasters' texels.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "material/raster_windows.hpp"

namespace carbtf::detail {

inline constexpr std::uint8_t kMaxFilterStride = 8;
inline constexpr std::uint8_t kRasterFilter = 9;
inline constexpr std::uint8_t kWindowFilter = 10;

// Where a payload holds rasters, for the raster and window filters.
struct RasterLayout {
  std::uint32_t skip = 0;
  std::uint8_t value_bytes = 1;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t rasters = 0;
  std::uint8_t rest_stride = 0;
  std::uint64_t values() const { return std::uint64_t{width} * height * rasters; }
  std::uint64_t end() const { return skip + values() * value_bytes; }
  // Whether the layout is well formed and its rasters lie within `size` bytes (without overflow).
  bool fits(std::uint64_t size) const;
};

enum class FilterDirection { apply, undo };

// Filter 0..kRasterFilter over `bytes` in place; `layout` is read by the raster filter only, and the
// caller has checked that it fits.
void run_filter(std::vector<std::uint8_t>& bytes, std::uint8_t filter, const RasterLayout& layout,
                FilterDirection direction);

// The layout of the window filter's stream: the source as one raster between the same bytes.
RasterLayout source_layout(const RasterLayout& rasters, const RasterWindows& windows);

// The window filter's stream before deflate (already under the raster filter), or nullopt where the
// rasters share no texels.
std::optional<std::pair<RasterWindows, std::vector<std::uint8_t>>> window_filtered(
    std::span<const std::uint8_t> payload, const RasterLayout& layout);

// The payload from the window filter's unfiltered stream (the skip bytes, the source values, the rest).
std::vector<std::uint8_t> expand_windows(const std::vector<std::uint8_t>& stream, const RasterLayout& layout,
                                         const RasterWindows& windows, std::uint32_t size);

}  // namespace carbtf::detail
