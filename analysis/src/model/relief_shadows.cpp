#include "carbtf/analysis/model/relief_shadows.hpp"

#include <cmath>
#include <stdexcept>

#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/engine/render/relief_horizons.hpp"

namespace carbtf {

std::vector<float> range_map_horizons(const Plane& range_map, double scale) {
  if (!(scale > 0.0)) return {};
  const auto rows = static_cast<std::uint32_t>(range_map.rows()),
             cols = static_cast<std::uint32_t>(range_map.cols());
  std::vector<float> heights(std::size_t{rows} * cols);
  for (std::uint32_t r = 0; r < rows; ++r) {
    for (std::uint32_t c = 0; c < cols; ++c)
      heights[std::size_t{r} * cols + c] = static_cast<float>(range_map(r, c));
  }
  std::vector<float> horizons;
  relief_horizons(heights, cols, rows, false, static_cast<float>(scale), horizons);
  return horizons;
}

namespace {

// The mean over the view's lights of RMS(I - k relit tone) / mean I, k matching the means (grey images).
double explained_error(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                       double light_z_floor, const std::vector<float>& horizons) {
  const Plane tone = relief_tone(dataset, view, range_map, light_z_floor, horizons);
  const auto cols = static_cast<Eigen::Index>(dataset.width());
  std::vector<float> rgb(dataset.pixel_count() * 3);
  Plane image(range_map.rows(), range_map.cols());
  double sum = 0.0;
  int count = 0;
  for (std::uint32_t l = 0; l < dataset.lights().size(); ++l) {
    const LightView pair{l, view};
    if (!dataset.has_image(pair)) continue;
    dataset.linear_rgb(pair, rgb);
    for (Eigen::Index i = 0; i < image.size(); ++i) {
      const auto p = static_cast<std::size_t>(i);
      image(i / cols, i % cols) = (rgb[3 * p] + rgb[3 * p + 1] + rgb[3 * p + 2]) / 3.0;
    }
    Plane model = relit_factor(range_map, dataset.lights()[l].vector(), light_z_floor, horizons) * tone;
    const double image_mean = image.mean(), model_mean = model.mean();
    if (!(image_mean > 0.0) || !(model_mean > 0.0)) continue;
    model *= image_mean / model_mean;
    sum += std::sqrt((image - model).square().mean()) / image_mean;
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace

ShadowFit fit_shadow_scale(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                           double light_z_floor) {
  if (range_map.rows() != static_cast<Eigen::Index>(dataset.height()) ||
      range_map.cols() != static_cast<Eigen::Index>(dataset.width())) {
    throw std::invalid_argument("fit_shadow_scale: the range map is not the dataset's size");
  }
  ShadowFit fit;
  double best = 0.0;
  for (const double scale : kShadowScales) {
    const double error =
        explained_error(dataset, view, range_map, light_z_floor, range_map_horizons(range_map, scale));
    if (scale == 0.0) {
      fit.error_without = fit.error = best = error;
    } else if (error < best) {
      best = error;
      fit.scale = scale;
      fit.error = error;
    }
  }
  if (fit.error > (1.0 - kShadowFitGain) * fit.error_without) {
    fit.scale = 0.0;
    fit.error = fit.error_without;
  }
  return fit;
}

}  // namespace carbtf
