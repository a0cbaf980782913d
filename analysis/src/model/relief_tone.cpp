#include "carbtf/analysis/model/relief_tone.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "carbtf/analysis/model/deshade.hpp"

namespace carbtf {

Plane relief_tone(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map, double light_z_floor) {
  const auto rows = static_cast<Eigen::Index>(dataset.height()), cols = static_cast<Eigen::Index>(dataset.width());
  if (range_map.rows() != rows || range_map.cols() != cols) throw std::invalid_argument("relief_tone: the range map is not the dataset's size");
  Plane measured = Plane::Zero(rows, cols);
  Plane explained = Plane::Zero(rows, cols);
  std::vector<float> rgb(dataset.pixel_count() * 3);
  Plane grey(rows, cols);
  for (std::uint32_t l = 0; l < dataset.lights().size(); ++l) {
    const LightView pair{l, view};
    if (!dataset.has_image(pair)) continue;
    dataset.linear_rgb(pair, rgb);
    for (Eigen::Index r = 0; r < rows; ++r) {
      for (Eigen::Index c = 0; c < cols; ++c) {
        const std::size_t p = static_cast<std::size_t>(r * cols + c);
        grey(r, c) = (rgb[3 * p] + rgb[3 * p + 1] + rgb[3 * p + 2]) / 3.0;
      }
    }
    const Plane relit = relit_factor(range_map, dataset.lights()[l].vector(), light_z_floor);
    const double relit_mean = relit.mean();
    if (relit_mean <= 0.0) continue;
    measured += grey;
    explained += relit * (grey.mean() / relit_mean);
  }
  if (explained.maxCoeff() <= 0.0) return Plane::Ones(rows, cols);
  // Where no light reaches a texel by the range map's account, nothing is known about its tone.
  return (explained > 0.0).select(measured / explained.max(1e-30), 1.0).max(kReliefToneFloor).min(kReliefToneCeiling);
}

void clamp_remainder(std::vector<Plane>& channels, double k) {
  for (Plane& channel : channels) {
    if (channel.size() == 0) continue;
    std::vector<double> values(static_cast<std::size_t>(channel.size()));
    Eigen::Map<Plane>(values.data(), channel.rows(), channel.cols()) = channel;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    const double median = *middle;
    for (double& v : values) v = std::abs(v - median);
    std::nth_element(values.begin(), middle, values.end());
    const double spread = k * 1.4826 * *middle;
    channel = channel.min(median + spread).max(median - spread);
  }
}

Plane weighted_tone(const Plane& tone, double weight) { return 1.0 + weight * (tone - 1.0); }

void apply_relief(std::span<float> rgb, const Plane& tone, const Plane& relit) {
  const auto pixels = static_cast<std::size_t>(tone.size());
  if (relit.rows() != tone.rows() || relit.cols() != tone.cols() || rgb.size() != pixels * 3) {
    throw std::invalid_argument("apply_relief: the image, the tone and the relit factor differ in size");
  }
  const std::size_t width = static_cast<std::size_t>(tone.cols());
  for (std::size_t p = 0; p < pixels; ++p) {
    const auto r = static_cast<Eigen::Index>(p / width), c = static_cast<Eigen::Index>(p % width);
    const auto factor = static_cast<float>(tone(r, c) * relit(r, c));
    for (std::size_t k = 0; k < 3; ++k) rgb[p * 3 + k] *= factor;
  }
}

void match_render_mean(std::vector<Plane>& smooth, const std::vector<Plane>& measured, const Plane& tone, const Plane& relit) {
  if (smooth.size() != measured.size()) throw std::invalid_argument("match_render_mean: channel counts differ");
  double smooth_mean = 0.0, target = 0.0;
  for (std::size_t c = 0; c < smooth.size(); ++c) smooth_mean += smooth[c].mean(), target += measured[c].mean();
  const double relief_mean = (tone * relit).mean();
  const double gain = target / (smooth_mean * relief_mean);
  if (!(smooth_mean > 0.0 && relief_mean > 0.0 && target > 0.0 && std::isfinite(gain))) return;
  for (Plane& channel : smooth) channel *= gain;
}

}  // namespace carbtf
