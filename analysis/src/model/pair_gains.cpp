#include "carbtf/analysis/model/pair_gains.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/parallax_view.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/analysis/segmentation/lab_histogram.hpp"
#include "carbtf/reference/parallel_for.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"

namespace carbtf {
namespace {

using Rgb = std::array<double, 3>;

// The Lab mean of `pixels` (interleaved linear RGB, negatives clamped as the measure clamps them),
// each channel times its gain, plus `highlight` (one grey value per pixel, which no gain scales) where
// given.
Rgb lab_mean(std::span<const float> pixels, const Rgb& gain, std::span<const float> highlight = {}) {
  Rgb sum{};
  const std::size_t count = pixels.size() / 3;
  for (std::size_t p = 0; p < count; ++p) {
    const double added = highlight.empty() ? 0.0 : highlight[p];
    const auto lab =
        linear_srgb_to_lab(static_cast<float>(gain[0] * std::max(pixels[3 * p], 0.0f) + added),
                           static_cast<float>(gain[1] * std::max(pixels[3 * p + 1], 0.0f) + added),
                           static_cast<float>(gain[2] * std::max(pixels[3 * p + 2], 0.0f) + added));
    for (int c = 0; c < 3; ++c) sum[c] += lab[c];
  }
  for (double& v : sum) v /= static_cast<double>(std::max<std::size_t>(count, 1));
  return sum;
}

// Gains within what a code holds.
double clamp_gain(double gain) {
  return std::clamp(gain, double{pair_gain_of_code(0)}, double{pair_gain_of_code(255)});
}

std::uint8_t gain_code(double gain) {
  const long code = std::lround(std::log2(clamp_gain(gain)) * kPairGainStepsPerOctave) + kPairGainZero;
  return static_cast<std::uint8_t>(std::clamp(code, 0l, 255l));
}

// The gains that move the model's Lab mean onto `target`: each step scales every channel by the ratio of
// the target's linear colour to the current mean's, which converges in a few steps where the model's
// contrast is near the measurement's.
Rgb solve_gains(std::span<const float> model, const Rgb& target, std::span<const float> highlight) {
  const Rgb wanted = lab_to_linear_srgb(target[0], target[1], target[2]);
  Rgb gain{1.0, 1.0, 1.0};
  for (int step = 0; step < 6; ++step) {
    const Rgb mean = lab_mean(model, gain, highlight);
    const double error = std::hypot(mean[0] - target[0], mean[1] - target[1], mean[2] - target[2]);
    if (error < 0.02) break;
    const Rgb current = lab_to_linear_srgb(mean[0], mean[1], mean[2]);
    for (int c = 0; c < 3; ++c) {
      if (current[c] > 1e-6 && wanted[c] > 1e-6) gain[c] = clamp_gain(gain[c] * wanted[c] / current[c]);
    }
  }
  return gain;
}

}  // namespace

std::vector<std::uint8_t> fit_pair_gains(const BtfDataset& dataset, const Material& material,
                                         const PairGainRelief& relief, std::uint64_t seed, unsigned threads,
                                         const std::function<void()>& progress) {
  const std::uint32_t width = dataset.width(), height = dataset.height();
  const std::size_t lights = dataset.lights().size(), views = dataset.views().size(), pairs = lights * views;
  if (material.lights.size() != lights || material.views.size() != views ||
      material.subspace_index.size() != pairs) {
    throw std::invalid_argument("fit_pair_gains: the material's directions are not the dataset's");
  }
  if (relief.range_map.rows() != height || relief.range_map.cols() != width)
    throw std::invalid_argument("fit_pair_gains: the range map is not the images' size");
  for (const SubspaceModel& s : material.subspaces) {
    if (s.channels != 3) throw std::invalid_argument("fit_pair_gains: pair gains need RGB subspace models");
  }
  // The sample grid: every stride-th pixel each way, about kPairGainSamples of them.
  const auto stride = static_cast<std::uint32_t>(
      std::max(1.0, std::floor(std::sqrt(static_cast<double>(dataset.pixel_count()) / kPairGainSamples))));
  std::vector<std::size_t> grid;
  for (std::uint32_t r = 0; r < height; r += stride)
    for (std::uint32_t c = 0; c < width; c += stride) grid.push_back(std::size_t{r} * width + c);

  // Per subspace, its synthesized smooth texture times its share of the tone.
  reference::SubspaceBlock block;
  block.seed = seed;
  block.width = width;
  block.height = height;
  std::vector<std::vector<float>> toned = reference::synthesize_subspaces(material, {}, block, threads);
  const std::vector<Plane> untoned{Plane::Ones(height, width)};
  for (std::size_t s = 0; s < material.subspaces.size(); ++s) {
    const std::vector<Plane> share =
        weighted_tone(relief.tone.empty() ? std::span<const Plane>(untoned) : relief.tone,
                      material.subspaces[s].tone_weight, material.range.tone_chroma);
    for (std::size_t p = 0; p < dataset.pixel_count(); ++p) {
      const auto r = static_cast<Eigen::Index>(p / width), c = static_cast<Eigen::Index>(p % width);
      for (int k = 0; k < 3; ++k)
        toned[s][3 * p + k] *= static_cast<float>(share[static_cast<std::size_t>(k)](r, c));
    }
  }
  // Per view, where each grid pixel of the render reads the textures.
  std::vector<ParallaxView> parallax;
  parallax.reserve(views);
  for (std::size_t v = 0; v < views; ++v)
    parallax.emplace_back(relief.range_map, dataset.views()[v].vector(), grid);

  std::vector<std::uint8_t> codes(3 * pairs, static_cast<std::uint8_t>(kPairGainZero));
  const double z_floor = relight_floor(material);
  detail::parallel_for(lights, threads, [&](std::size_t l) {
    const Plane relit_plane =
        relit_factor(relief.range_map, dataset.lights()[l].vector(), z_floor, relief.horizons);
    std::vector<float> relit(dataset.pixel_count());
    for (std::size_t p = 0; p < relit.size(); ++p)
      relit[p] = static_cast<float>(
          relit_plane(static_cast<Eigen::Index>(p / width), static_cast<Eigen::Index>(p % width)));
    std::vector<float> image(dataset.pixel_count() * 3), measured(grid.size() * 3), model(grid.size() * 3),
        highlight;
    std::vector<float> lobe(relief.specular.strength > 0.0 ? dataset.pixel_count() : 0);
    for (std::size_t v = 0; v < views; ++v) {
      const LightView pair{static_cast<std::uint32_t>(l), static_cast<std::uint32_t>(v)};
      if (!dataset.has_image(pair)) continue;
      dataset.linear_rgb(pair, image);
      if (!lobe.empty()) {
        const Plane plane = lobe_of(relief.specular, relief.range_map, dataset.lights()[l].vector(),
                                    dataset.views()[v].vector(), relief.horizons);
        for (std::size_t p = 0; p < lobe.size(); ++p)
          lobe[p] = static_cast<float>(
              plane(static_cast<Eigen::Index>(p / width), static_cast<Eigen::Index>(p % width)));
        highlight.resize(grid.size());
      }
      const float* base = toned[subspace_of(material, pair.light, pair.view)].data();
      const ParallaxView& view = parallax[v];
      for (std::size_t i = 0; i < grid.size(); ++i) {
        const float factor = view.sample(relit.data(), 1, i, 0);
        if (!lobe.empty()) highlight[i] = view.sample(lobe.data(), 1, i, 0);
        for (std::size_t k = 0; k < 3; ++k) {
          measured[3 * i + k] = image[3 * grid[i] + k];
          model[3 * i + k] = view.sample(base, 3, i, k) * factor;
        }
      }
      const Rgb target = lab_mean(measured, {1.0, 1.0, 1.0});
      if (!(target[0] > 0.5) || !(lab_mean(model, {1.0, 1.0, 1.0})[0] > 0.5))
        continue;  // black: nothing to match
      const Rgb gain = solve_gains(model, target, highlight);
      for (std::size_t c = 0; c < 3; ++c) codes[c * pairs + l * views + v] = gain_code(gain[c]);
    }
    if (progress) progress();
  });
  return codes;
}

}  // namespace carbtf
