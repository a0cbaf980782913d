// Summary statistics of a 2D scalar field, accumulated in double. Used to check noise and, later,
// synthesized bands against their models.
#pragma once

#include <cstdint>
#include <span>

namespace carbtf {

struct FieldStatistics {
  std::uint64_t count = 0;
  double mean = 0;
  double variance = 0;         // population variance
  double skewness = 0;         // third standardized moment
  double excess_kurtosis = 0;  // fourth standardized moment minus 3
  double lag1_horizontal = 0;  // correlation of (r, c) with (r, c + 1)
  double lag1_vertical = 0;    // correlation of (r, c) with (r + 1, c)
  float min = 0;
  float max = 0;
};

// `values` holds width * height samples, row-major.
FieldStatistics field_statistics(std::span<const float> values, std::uint32_t width, std::uint32_t height);

}  // namespace carbtf
