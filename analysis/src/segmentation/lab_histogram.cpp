#include "carbtf/analysis/segmentation/lab_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace carbtf {
namespace {

// The CIE L*a*b* companding function f(t).
float lab_f(float t) {
  constexpr float delta = 6.0f / 29.0f;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
}

std::uint32_t bin_of(float value, float low, float high, std::uint32_t bins) {
  const float position = (value - low) / (high - low) * static_cast<float>(bins);
  if (!(position > 0.0f)) return 0;  // also NaN
  return std::min(bins - 1, static_cast<std::uint32_t>(position));
}

}  // namespace

std::array<float, 3> linear_srgb_to_lab(float r, float g, float b) {
  // sRGB primaries to XYZ (IEC 61966-2-1), divided by the D65 white point.
  const float x = (0.4124564f * r + 0.3575761f * g + 0.1804375f * b) / 0.95047f;
  const float y = 0.2126729f * r + 0.7151522f * g + 0.0721750f * b;
  const float z = (0.0193339f * r + 0.1191920f * g + 0.9503041f * b) / 1.08883f;
  const float fx = lab_f(x), fy = lab_f(y), fz = lab_f(z);
  return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

std::array<double, 3> lab_to_linear_srgb(double l, double a, double b) {
  constexpr double delta = 6.0 / 29.0;
  const auto inverse_f = [](double f) {
    return f > delta ? f * f * f : 3.0 * delta * delta * (f - 4.0 / 29.0);
  };
  const double fy = (l + 16.0) / 116.0;
  const double x = 0.95047 * inverse_f(fy + a / 500.0), y = inverse_f(fy),
               z = 1.08883 * inverse_f(fy - b / 200.0);
  // XYZ to linear sRGB (IEC 61966-2-1).
  return {3.2404542 * x - 1.5371385 * y - 0.4985314 * z, -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
          0.0556434 * x - 0.2040259 * y + 1.0572252 * z};
}

std::vector<float> lab_cumulative_histogram(std::span<const float> rgb, std::uint32_t width,
                                            std::uint32_t height, std::uint32_t bins, std::uint32_t stride) {
  if (bins == 0 || stride == 0)
    throw std::invalid_argument("a Lab histogram needs at least one bin and a positive stride");
  if (rgb.size() < std::size_t{width} * height * 3)
    throw std::invalid_argument("Lab histogram: image buffer too small");
  std::vector<float> feature(std::size_t{bins} * 3, 0.0f);
  std::size_t count = 0;
  for (std::uint32_t row = 0; row < height; row += stride) {
    for (std::uint32_t col = 0; col < width; col += stride) {
      const float* p = rgb.data() + (std::size_t{row} * width + col) * 3;
      const auto lab = linear_srgb_to_lab(p[0], p[1], p[2]);
      feature[bin_of(lab[0], 0.0f, 100.0f, bins)] += 1.0f;
      feature[bins + bin_of(lab[1], -110.0f, 110.0f, bins)] += 1.0f;
      feature[2 * bins + bin_of(lab[2], -110.0f, 110.0f, bins)] += 1.0f;
      ++count;
    }
  }
  if (count == 0) return feature;
  for (std::uint32_t channel = 0; channel < 3; ++channel) {
    float running = 0.0f;
    for (std::uint32_t i = 0; i < bins; ++i) {
      running += feature[channel * bins + i];
      feature[channel * bins + i] = running / static_cast<float>(count);
    }
  }
  return feature;
}

}  // namespace carbtf
