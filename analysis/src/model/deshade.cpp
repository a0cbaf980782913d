#include "carbtf/analysis/model/deshade.hpp"

#include "carbtf/engine/render/material_tables.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "carbtf/engine/render/relief_horizons.hpp"

namespace carbtf {

RangeFacet range_map_facet(const Plane& range_map, Eigen::Index row, Eigen::Index col) {
  const Eigen::Index rows = range_map.rows(), cols = range_map.cols();
  auto h = [&](Eigen::Index r, Eigen::Index c) {
    return range_map(std::clamp<Eigen::Index>(r, 0, rows - 1), std::clamp<Eigen::Index>(c, 0, cols - 1));
  };
  const double dx = 0.5 * (h(row, col + 1) - h(row, col - 1));
  const double dy = 0.5 * (h(row - 1, col) - h(row + 1, col));
  return {dx, dy, std::sqrt(dx * dx + dy * dy + 1.0)};
}

double horizon_visibility(std::span<const float> horizons, Eigen::Index texel,
                          const std::array<double, 3>& light) {
  if (horizons.empty()) return 1.0;
  constexpr std::size_t n = kReliefHorizonDirections;
  return relief_visibility(
      horizons.subspan(static_cast<std::size_t>(texel) * n).first<n>(),
      {static_cast<float>(light[0]), static_cast<float>(light[1]), static_cast<float>(light[2])});
}

Plane relit_factor(const Plane& range_map, const std::array<double, 3>& light, double light_z_floor,
                   std::span<const float> horizons) {
  const Eigen::Index rows = range_map.rows(), cols = range_map.cols();
  if (!horizons.empty() &&
      horizons.size() != static_cast<std::size_t>(rows * cols) * kReliefHorizonDirections) {
    throw std::invalid_argument("relit_factor: the horizons are not the range map's");
  }
  Plane factor(rows, cols);
  const double denominator = std::max(light[2], light_z_floor);
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      factor(r, c) = std::max(range_map_facet(range_map, r, c).cosine(light), 0.0) / denominator;
      if (!horizons.empty()) factor(r, c) *= horizon_visibility(horizons, r * cols + c, light);
      factor(r, c) = kReliefAmbient + (1.0 - kReliefAmbient) * factor(r, c);
    }
  }
  return factor;
}

void divide_shading(std::vector<Plane>& channels, const Plane& factor, double floor) {
  for (Plane& channel : channels) {
    if (channel.rows() != factor.rows() || channel.cols() != factor.cols())
      throw std::invalid_argument("divide_shading: sizes differ");
    channel /= factor.max(floor);
  }
}

void divide_shading(std::vector<Plane>& channels, const std::vector<Plane>& factors, double floor) {
  if (factors.size() != channels.size())
    throw std::invalid_argument("divide_shading: one factor per channel");
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (channels[c].rows() != factors[c].rows() || channels[c].cols() != factors[c].cols())
      throw std::invalid_argument("divide_shading: sizes differ");
    channels[c] /= factors[c].max(floor);
  }
}

void undo_parallax(std::vector<Plane>& channels, const Plane& range_map, const std::array<double, 3>& view,
                   double scale) {
  const Eigen::Index rows = range_map.rows(), cols = range_map.cols();
  const double mean = range_map.mean();
  const double view_z = std::max(view[2], double{kParallaxMinViewZ});
  for (Plane& channel : channels) {
    if (channel.rows() != rows || channel.cols() != cols)
      throw std::invalid_argument("undo_parallax: sizes differ");
    const Plane measured = channel;
    auto at = [&](Eigen::Index r, Eigen::Index c) {
      return measured(std::clamp<Eigen::Index>(r, 0, rows - 1), std::clamp<Eigen::Index>(c, 0, cols - 1));
    };
    for (Eigen::Index r = 0; r < rows; ++r) {
      for (Eigen::Index c = 0; c < cols; ++c) {
        // The texel at height h is what the ray through the plane point h tan(theta) back along the view
        // meets (the render pass's march, parallax_march.hpp), where no ridge hides it.
        const double shift = scale * (range_map(r, c) - mean) / view_z;
        const double x = static_cast<double>(c) - shift * view[0];
        const double y = static_cast<double>(r) + shift * view[1];
        const double x0 = std::floor(x), y0 = std::floor(y);
        const double fx = x - x0, fy = y - y0;
        const auto c0 = static_cast<Eigen::Index>(x0), r0 = static_cast<Eigen::Index>(y0);
        const double top = (1.0 - fx) * at(r0, c0) + fx * at(r0, c0 + 1);
        const double bottom = (1.0 - fx) * at(r0 + 1, c0) + fx * at(r0 + 1, c0 + 1);
        channel(r, c) = (1.0 - fy) * top + fy * bottom;
      }
    }
  }
}

}  // namespace carbtf
