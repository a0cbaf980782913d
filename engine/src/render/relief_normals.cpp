#include "carbtf/engine/render/relief_normals.hpp"

#include <cmath>

namespace carbtf {

void store_normal_lengths(std::span<float> rgba) {
  for (std::size_t i = 0; i + 3 < rgba.size(); i += 4)
    rgba[i + 3] = std::sqrt(rgba[i] * rgba[i] + rgba[i + 1] * rgba[i + 1] + rgba[i + 2] * rgba[i + 2]);
}

void relief_normals(std::span<const float> heights, std::uint32_t width, std::uint32_t height, bool wrap,
                    std::vector<float>& out) {
  out.assign(std::size_t{width} * height * 3, 0.0f);
  if (width == 0 || height == 0 || heights.size() != std::size_t{width} * height) return;
  const auto neighbour = [wrap](std::uint32_t i, int step, std::uint32_t size) {
    const std::int64_t j = static_cast<std::int64_t>(i) + step;
    if (wrap) return static_cast<std::uint32_t>((j + size) % size);
    return static_cast<std::uint32_t>(j < 0 ? 0 : j >= size ? size - 1 : j);
  };
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const auto h = [&](std::uint32_t cx, std::uint32_t cy) {
        return heights[std::size_t{cy} * width + cx];
      };
      const float dx = 0.5f * (h(neighbour(x, 1, width), y) - h(neighbour(x, -1, width), y));
      const float dy = 0.5f * (h(x, neighbour(y, -1, height)) - h(x, neighbour(y, 1, height)));
      const float length = std::sqrt(dx * dx + dy * dy + 1.0f);
      float* n = &out[(std::size_t{y} * width + x) * 3];
      n[0] = -dx / length;
      n[1] = -dy / length;
      n[2] = 1.0f / length;
    }
  }
}

}  // namespace carbtf
