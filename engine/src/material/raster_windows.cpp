#include "material/raster_windows.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

#include "material/raster_prediction.hpp"

namespace carbtf::detail {
namespace {

// Texel comparisons one search may make: far more than four 128^2 patches need (about 10^5), few
// enough (well under a second) that rasters built to defeat the early exits cannot stall an encode.
constexpr std::uint64_t kComparisonBudget = std::uint64_t{1} << 26;

struct Offset {
  std::int64_t dr = 0, dc = 0;
  std::uint64_t area = 0;  // texels two windows at this offset share
};

// Every offset at which two windows overlap, the largest overlap first (ties in a fixed order).
std::vector<Offset> overlapping_offsets(std::uint32_t width, std::uint32_t height) {
  std::vector<Offset> offsets;
  offsets.reserve((2 * std::size_t{width} - 1) * (2 * std::size_t{height} - 1));
  for (std::int64_t dr = 1 - std::int64_t{height}; dr < height; ++dr) {
    for (std::int64_t dc = 1 - std::int64_t{width}; dc < width; ++dc) {
      offsets.push_back({dr, dc,
                         static_cast<std::uint64_t>(height - std::llabs(dr)) *
                             static_cast<std::uint64_t>(width - std::llabs(dc))});
    }
  }
  std::stable_sort(offsets.begin(), offsets.end(),
                   [](const Offset& a, const Offset& b) { return a.area > b.area; });
  return offsets;
}

class WindowSearch {
 public:
  WindowSearch(const std::vector<std::uint32_t>& values, std::uint32_t width, std::uint32_t height)
      : values_(values), width_(width), height_(height) {}

  // Whether raster `r` at (row, col) agrees with every placed raster it overlaps there; `shared` adds
  // up those overlaps (a texel that two of them cover counts twice: close enough to rank placements).
  bool agrees(std::size_t r, std::int64_t row, std::int64_t col, std::uint64_t& shared) {
    shared = 0;
    for (std::size_t p = 0; p < placed_rows_.size(); ++p) {
      const std::int64_t top = std::max(row, placed_rows_[p]);
      const std::int64_t bottom = std::min(row + height_, placed_rows_[p] + height_);
      const std::int64_t left = std::max(col, placed_cols_[p]);
      const std::int64_t right = std::min(col + width_, placed_cols_[p] + width_);
      if (top >= bottom || left >= right) continue;
      for (std::int64_t y = top; y < bottom; ++y) {
        const std::uint32_t* a = raster(r) + (y - row) * width_ + (left - col);
        const std::uint32_t* b = raster(p) + (y - placed_rows_[p]) * width_ + (left - placed_cols_[p]);
        for (std::int64_t x = 0; x < right - left; ++x) {
          if (++comparisons_ > kComparisonBudget) return false;
          if (a[x] != b[x]) return false;
        }
      }
      shared += static_cast<std::uint64_t>((bottom - top) * (right - left));
    }
    return true;
  }

  bool exhausted() const { return comparisons_ > kComparisonBudget; }
  void place(std::int64_t row, std::int64_t col) {
    placed_rows_.push_back(row);
    placed_cols_.push_back(col);
  }
  const std::vector<std::int64_t>& rows() const { return placed_rows_; }
  const std::vector<std::int64_t>& cols() const { return placed_cols_; }

 private:
  const std::uint32_t* raster(std::size_t r) const { return values_.data() + r * width_ * height_; }

  const std::vector<std::uint32_t>& values_;
  std::int64_t width_, height_;
  std::vector<std::int64_t> placed_rows_, placed_cols_;
  std::uint64_t comparisons_ = 0;
};

}  // namespace

std::optional<RasterWindows> find_raster_windows(const std::vector<std::uint32_t>& values,
                                                 std::uint32_t width, std::uint32_t height,
                                                 std::uint32_t count) {
  if (count < 2 || width == 0 || height == 0 || values.size() != std::size_t{width} * height * count)
    return std::nullopt;
  const std::vector<Offset> offsets = overlapping_offsets(width, height);
  WindowSearch search(values, width, height);
  search.place(0, 0);
  for (std::uint32_t r = 1; r < count; ++r) {
    std::uint64_t best_shared = 0;
    std::int64_t best_row = 0, best_col = 0;
    for (std::size_t p = 0; p < r && !search.exhausted(); ++p) {
      for (const Offset& o : offsets) {
        if (o.area <= best_shared || search.exhausted()) break;  // later offsets share less with p
        std::uint64_t shared = 0;
        const std::int64_t row = search.rows()[p] + o.dr, col = search.cols()[p] + o.dc;
        if (search.agrees(r, row, col, shared) && shared > best_shared) {
          best_shared = shared, best_row = row, best_col = col;
          break;  // the first agreement with p shares the most with it
        }
      }
    }
    if (best_shared == 0) {  // nothing shared: beside the others, in a column of its own
      best_row = *std::min_element(search.rows().begin(), search.rows().end());
      best_col = *std::max_element(search.cols().begin(), search.cols().end()) + width;
    }
    search.place(best_row, best_col);
  }
  const std::int64_t top = *std::min_element(search.rows().begin(), search.rows().end());
  const std::int64_t left = *std::min_element(search.cols().begin(), search.cols().end());
  RasterWindows windows;
  for (std::uint32_t r = 0; r < count; ++r) {
    windows.rows.push_back(static_cast<std::uint32_t>(search.rows()[r] - top));
    windows.cols.push_back(static_cast<std::uint32_t>(search.cols()[r] - left));
    windows.source_height = std::max(windows.source_height, windows.rows.back() + height);
    windows.source_width = std::max(windows.source_width, windows.cols.back() + width);
  }
  if (windows.source_texels() >= std::uint64_t{width} * height * count) return std::nullopt;
  return windows;
}

std::vector<std::uint32_t> compose_window_source(const std::vector<std::uint32_t>& values,
                                                 std::uint32_t width, std::uint32_t height,
                                                 const RasterWindows& windows) {
  const std::size_t source_width = windows.source_width;
  std::vector<std::uint32_t> source(static_cast<std::size_t>(windows.source_texels()));
  std::vector<bool> covered(source.size(), false);
  for (std::size_t r = 0; r < windows.rows.size(); ++r) {
    for (std::uint32_t y = 0; y < height; ++y) {
      for (std::uint32_t x = 0; x < width; ++x) {
        const std::size_t at = (windows.rows[r] + std::size_t{y}) * source_width + windows.cols[r] + x;
        source[at] = values[(r * height + y) * width + x];
        covered[at] = true;
      }
    }
  }
  for (std::uint32_t y = 0; y < windows.source_height; ++y) {
    for (std::uint32_t x = 0; x < windows.source_width; ++x) {
      const std::size_t at = y * source_width + x;
      if (!covered[at]) source[at] = raster_prediction(source.data(), windows.source_width, x, y);
    }
  }
  return source;
}

}  // namespace carbtf::detail
