#include "carbtf/analysis/model/parallax_view.hpp"

#include <glm/glm.hpp>

#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/engine/render/material_tables.hpp"
#include "carbtf/reference/parallax_march.hpp"

namespace carbtf {

ParallaxView::ParallaxView(const Plane& range_map, const std::array<double, 3>& view,
                           std::span<const std::size_t> pixels) {
  const auto width = static_cast<std::size_t>(range_map.cols()),
             height = static_cast<std::size_t>(range_map.rows());
  const glm::vec2 size(static_cast<float>(width), static_cast<float>(height));
  const auto tap_at = [&](glm::vec2 uv) {
    const glm::vec2 t = glm::clamp(uv * size - 0.5f, glm::vec2(0.0f), size - 1.0f);
    const auto c0 = static_cast<std::size_t>(t.x), r0 = static_cast<std::size_t>(t.y);
    return Tap{r0 * width + c0, c0 + 1 < width ? std::size_t{1} : 0, r0 + 1 < height ? width : 0,
               t.x - static_cast<float>(c0), t.y - static_cast<float>(r0)};
  };
  // The render's heights: float, minus their mean.
  std::vector<float> heights(width * height);
  for (std::size_t i = 0; i < heights.size(); ++i)
    heights[i] = static_cast<float>(
        range_map(static_cast<Eigen::Index>(i / width), static_cast<Eigen::Index>(i % width)));
  const ReliefExtent extent = relief_extent(heights, static_cast<float>(kAnalysisParallaxScale));
  const auto height_at = [&](glm::vec2 uv) { return read(heights.data(), 1, tap_at(uv), 0) - extent.mean; };
  const glm::vec3 direction(static_cast<float>(view[0]), static_cast<float>(view[1]),
                            static_cast<float>(view[2]));
  const std::size_t count = pixels.empty() ? width * height : pixels.size();
  taps_.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t p = pixels.empty() ? i : pixels[i];
    const glm::vec2 centre(static_cast<float>(p % width) + 0.5f, static_cast<float>(p / width) + 0.5f);
    taps_[i] = tap_at(reference::parallax_march(height_at, centre / size, direction, size,
                                                static_cast<float>(kAnalysisParallaxScale), extent,
                                                kDefaultParallaxSteps));
  }
}

float ParallaxView::sample(const float* texture, std::size_t channels, std::size_t i, std::size_t k) const {
  return read(texture, channels, taps_[i], k);
}

float ParallaxView::read(const float* texture, std::size_t channels, const Tap& t, std::size_t k) {
  const auto at = [&](std::size_t texel) { return texture[texel * channels + k]; };
  const float top = at(t.texel) + t.fx * (at(t.texel + t.right) - at(t.texel));
  const float bottom = at(t.texel + t.down) + t.fx * (at(t.texel + t.down + t.right) - at(t.texel + t.down));
  return top + t.fy * (bottom - top);
}

std::vector<float> ParallaxView::shown(std::span<const float> texture, std::size_t channels) const {
  std::vector<float> out(taps_.size() * channels);
  for (std::size_t i = 0; i < taps_.size(); ++i)
    for (std::size_t k = 0; k < channels; ++k) out[i * channels + k] = sample(texture.data(), channels, i, k);
  return out;
}

}  // namespace carbtf
