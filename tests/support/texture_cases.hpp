// Test images for the texture measures: a sample material rendered under one light, and the mild
// distortions a person still calls the same material (docs/design.md 5).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "carbtf/analysis/quality/texture_references.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"

namespace carbtf::test {

inline constexpr std::uint32_t kSize = 256;

// One rendered image of a sample material, kSize^2: top view, light at `theta` degrees from azimuth `phi`.
inline RgbField rendered_sample(const std::string& name, double theta, double phi = 30.0) {
  const Surface surface = make_sample_surface(name, kSize, 1);
  RgbField image{std::vector<float>(std::size_t{kSize} * kSize * 3), kSize, kSize};
  RenderOptions options;
  options.progress = false;
  render_btf(surface, {Direction::from_degrees(theta, phi)}, {Direction::from_degrees(0.0, 0.0)}, options,
             [&](std::uint32_t, std::uint32_t, std::span<const float> rgb) {
               std::copy(rgb.begin(), rgb.end(), image.rgb.begin());
             });
  return image;
}

// Separable Gaussian blur, clamped at the borders.
inline RgbField blurred(const RgbField& in, double sigma) {
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> kernel;
  double total = 0.0;
  for (int i = -radius; i <= radius; ++i)
    total += kernel.emplace_back(std::exp(-0.5 * i * i / (sigma * sigma)));
  RgbField tmp = in, out = in;
  const int w = static_cast<int>(in.width), h = static_cast<int>(in.height);
  auto at = [&](const RgbField& f, int r, int c, int ch) {
    return f
        .rgb[(std::size_t(std::clamp(r, 0, h - 1)) * in.width + std::size_t(std::clamp(c, 0, w - 1))) * 3 +
             std::size_t(ch)];
  };
  for (int pass = 0; pass < 2; ++pass) {
    const RgbField& src = pass == 0 ? in : tmp;
    RgbField& dst = pass == 0 ? tmp : out;
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c)
        for (int ch = 0; ch < 3; ++ch) {
          double sum = 0.0;
          for (int i = -radius; i <= radius; ++i)
            sum +=
                kernel[std::size_t(i + radius)] * (pass == 0 ? at(src, r, c + i, ch) : at(src, r + i, c, ch));
          dst.rgb[(std::size_t(r) * in.width + std::size_t(c)) * 3 + std::size_t(ch)] =
              static_cast<float>(sum / total);
        }
  }
  return out;
}

// Hue rotation by `degrees` about the grey axis of linear RGB (Rodrigues), clamped at 0.
inline RgbField hue_shifted(const RgbField& in, double degrees) {
  const double a = degrees * std::numbers::pi / 180.0, cs = std::cos(a), sn = std::sin(a),
               k = (1.0 - cs) / 3.0, s3 = sn / std::sqrt(3.0);
  const double m[3][3] = {{cs + k, k - s3, k + s3}, {k + s3, cs + k, k - s3}, {k - s3, k + s3, cs + k}};
  RgbField out = in;
  for (std::size_t p = 0; p < in.rgb.size() / 3; ++p) {
    for (int i = 0; i < 3; ++i) {
      double v = 0.0;
      for (int j = 0; j < 3; ++j) v += m[i][j] * in.rgb[p * 3 + std::size_t(j)];
      out.rgb[p * 3 + std::size_t(i)] = std::max(0.0f, static_cast<float>(v));
    }
  }
  return out;
}

// A quarter turn clockwise.
inline RgbField rotated(const RgbField& in) {
  RgbField out{std::vector<float>(in.rgb.size()), in.height, in.width};
  for (std::uint32_t r = 0; r < in.height; ++r)
    for (std::uint32_t c = 0; c < in.width; ++c)
      for (int ch = 0; ch < 3; ++ch)
        out.rgb[(std::size_t(c) * out.width + (in.height - 1 - r)) * 3 + std::size_t(ch)] =
            in.rgb[(std::size_t(r) * in.width + c) * 3 + std::size_t(ch)];
  return out;
}

// Linear light times `gain`.
inline RgbField brighter(const RgbField& in, double gain) {
  RgbField out = in;
  for (float& v : out.rgb) v = static_cast<float>(v * gain);
  return out;
}

}  // namespace carbtf::test
