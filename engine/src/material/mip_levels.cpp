#include "carbtf/engine/material/mip_levels.hpp"

#include <glm/common.hpp>

namespace carbtf {

std::vector<float> next_mip_level(std::span<const float> level, std::uint32_t width, std::uint32_t height,
                                  std::uint32_t channels) {
  const std::uint32_t w = width / 2, h = height / 2;
  std::vector<float> out(std::size_t{w} * h * channels);
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      for (std::uint32_t c = 0; c < channels; ++c) {
        const auto at = [&](std::uint32_t sx, std::uint32_t sy) {
          return level[(std::size_t{sy} * width + sx) * channels + c];
        };
        const float top = glm::mix(at(2 * x, 2 * y), at(2 * x + 1, 2 * y), 0.5f);
        const float bottom = glm::mix(at(2 * x, 2 * y + 1), at(2 * x + 1, 2 * y + 1), 0.5f);
        out[(std::size_t{y} * w + x) * channels + c] = glm::mix(top, bottom, 0.5f);
      }
    }
  }
  return out;
}

}  // namespace carbtf
