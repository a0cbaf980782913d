#include "carbtf/analysis/field_statistics.hpp"

#include <algorithm>
#include <cmath>

namespace carbtf {

FieldStatistics field_statistics(std::span<const float> values, std::uint32_t width, std::uint32_t height) {
  FieldStatistics s;
  s.count = std::uint64_t{width} * height;
  if (s.count == 0) return s;
  double sum = 0;
  s.min = s.max = values[0];
  for (std::uint64_t i = 0; i < s.count; ++i) {
    sum += values[i];
    s.min = std::min(s.min, values[i]);
    s.max = std::max(s.max, values[i]);
  }
  s.mean = sum / static_cast<double>(s.count);
  // Central moments in a second pass: no cancellation from large means.
  double m2 = 0, m3 = 0, m4 = 0, horizontal = 0, vertical = 0;
  for (std::uint32_t r = 0; r < height; ++r) {
    for (std::uint32_t c = 0; c < width; ++c) {
      const std::size_t i = std::size_t{r} * width + c;
      const double d = values[i] - s.mean;
      const double d2 = d * d;
      m2 += d2;
      m3 += d2 * d;
      m4 += d2 * d2;
      if (c + 1 < width) horizontal += d * (values[i + 1] - s.mean);
      if (r + 1 < height) vertical += d * (values[i + width] - s.mean);
    }
  }
  const double n = static_cast<double>(s.count);
  s.variance = m2 / n;
  if (s.variance > 0) {
    s.skewness = (m3 / n) / std::pow(s.variance, 1.5);
    s.excess_kurtosis = (m4 / n) / (s.variance * s.variance) - 3.0;
    if (width > 1) s.lag1_horizontal = horizontal / (double(width - 1) * height) / s.variance;
    if (height > 1) s.lag1_vertical = vertical / (double(height - 1) * width) / s.variance;
  }
  return s;
}

}  // namespace carbtf
