#include "carbtf/engine/render/relief_horizons.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <carbtf_gpu_shared.h>

namespace carbtf {

static_assert(kReliefShadowSoftness == gpu::CARBTF_RELIEF_SHADOW_SOFTNESS,
              "the shader's penumbra is the CPU's");

void relief_horizons(std::span<const float> heights, std::uint32_t width, std::uint32_t height, bool wrap,
                     float scale, std::vector<float>& out) {
  constexpr std::uint32_t n = kReliefHorizonDirections;
  out.assign(std::size_t{width} * height * n, 0.0f);
  if (width == 0 || height == 0 || heights.size() != std::size_t{width} * height) return;
  // Whole-texel steps along the 8 azimuths (y up is row - 1), so no height is interpolated.
  constexpr int step_x[n] = {1, 1, 0, -1, -1, -1, 0, 1};
  constexpr int step_row[n] = {0, -1, -1, -1, 0, 1, 1, 1};
  // Tables, so the inner loop only reads: 1 / distance of step t along azimuth k, and the address of
  // step t along each axis from every column and row, wrapped or clamped (a 1024^2 map took 535 ms
  // with the addresses and divisions in the loop, 56-103 ms with the tables).
  std::array<std::array<float, kReliefHorizonReach + 1>, n> inverse_distance{};
  for (std::uint32_t k = 0; k < n; ++k) {
    const float step = (step_x[k] != 0 && step_row[k] != 0) ? std::numbers::sqrt2_v<float> : 1.0f;
    for (std::uint32_t t = 1; t <= kReliefHorizonReach; ++t)
      inverse_distance[k][t] = 1.0f / (step * static_cast<float>(t));
  }
  const auto address = [wrap](std::int64_t j, std::uint32_t size) {
    if (wrap) return static_cast<std::uint32_t>(((j % size) + size) % size);
    return static_cast<std::uint32_t>(std::clamp<std::int64_t>(j, 0, std::int64_t{size} - 1));
  };
  std::vector<std::uint32_t> column(std::size_t{width} * n * kReliefHorizonReach),
      row(std::size_t{height} * n * kReliefHorizonReach);
  for (std::uint32_t k = 0; k < n; ++k) {
    for (std::uint32_t t = 1; t <= kReliefHorizonReach; ++t) {
      for (std::uint32_t x = 0; x < width; ++x)
        column[(std::size_t{x} * n + k) * kReliefHorizonReach + t - 1] =
            address(std::int64_t{x} + std::int64_t{step_x[k]} * t, width);
      for (std::uint32_t y = 0; y < height; ++y)
        row[(std::size_t{y} * n + k) * kReliefHorizonReach + t - 1] =
            address(std::int64_t{y} + std::int64_t{step_row[k]} * t, height);
    }
  }
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const float h0 = heights[std::size_t{y} * width + x];
      float* horizon = &out[(std::size_t{y} * width + x) * n];
      for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t* cx = &column[(std::size_t{x} * n + k) * kReliefHorizonReach];
        const std::uint32_t* cy = &row[(std::size_t{y} * n + k) * kReliefHorizonReach];
        float best = 0.0f;
        for (std::uint32_t t = 1; t <= kReliefHorizonReach; ++t) {
          best = std::max(
              best, (heights[std::size_t{cy[t - 1]} * width + cx[t - 1]] - h0) * inverse_distance[k][t]);
        }
        horizon[k] = scale * best;
      }
    }
  }
}

void horizon_layer(std::span<const float> horizons, std::size_t texels, std::uint32_t half,
                   std::vector<float>& out) {
  out.assign(texels * 4, 0.0f);
  if (horizons.size() != texels * kReliefHorizonDirections) return;
  for (std::size_t i = 0; i < texels; ++i) {
    for (std::size_t k = 0; k < 4; ++k)
      out[4 * i + k] = horizons[kReliefHorizonDirections * i + 4 * half + k];
  }
}

float relief_visibility(std::span<const float, kReliefHorizonDirections> horizons,
                        const std::array<float, 3>& light) {
  const float across = std::sqrt(light[0] * light[0] + light[1] * light[1]);
  if (!(across > 0.0f)) return 1.0f;  // overhead: nothing rises above the zenith
  const float sector = std::atan2(light[1], light[0]) * (4.0f / std::numbers::pi_v<float>);
  const float base = std::floor(sector);
  const int k0 = (static_cast<int>(base) % 8 + 8) % 8, k1 = (k0 + 1) % 8;
  const float h0 = horizons[static_cast<std::size_t>(k0)], h1 = horizons[static_cast<std::size_t>(k1)];
  const float horizon = h0 + (sector - base) * (h1 - h0);
  return std::clamp(0.5f + (light[2] / across - horizon) / kReliefShadowSoftness, 0.0f, 1.0f);
}

}  // namespace carbtf
