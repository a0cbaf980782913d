#include "carbtf/analysis/quality/subspace_fidelity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/relief_shadows.hpp"
#include "carbtf/analysis/model/relief_specular.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/engine/material/range_tiles.hpp"

namespace carbtf {

std::vector<RgbField> representative_images(const BtfDataset& dataset, const Material& material) {
  std::vector<RgbField> measured;
  for (const SubspaceModel& s : material.subspaces) {
    if (!dataset.has_image({s.light, s.view})) {
      throw std::invalid_argument(dataset.source + ": the image of light " + std::to_string(s.light) +
                                  " view " + std::to_string(s.view) + " is missing");
    }
    RgbField image{std::vector<float>(dataset.pixel_count() * 3), dataset.width(), dataset.height()};
    dataset.linear_rgb({s.light, s.view}, image.rgb);
    measured.push_back(std::move(image));
  }
  return measured;
}

SubspaceFidelity subspace_fidelity(const Material& material, const SynthesizedImages& images,
                                   const std::vector<RgbField>& measured) {
  const std::uint32_t w = images.width, h = images.height;
  std::vector<float> heights(std::size_t{w} * h, 0.0f);
  std::vector<std::vector<float>> tones(3, std::vector<float>(heights.size(), 1.0f));
  if (material.range.tile_size > 0) {
    enlarge_range_map(material.range, {1, 0, 0, w, h}, heights);
    for (std::size_t k = 0; k < 3; ++k)
      enlarge_range_map(material.range, {1, 0, 0, w, h}, tones[k], tone_channel(k));
  }
  Plane height_plane(h, w);
  std::vector<Plane> tone(3, Plane(h, w));
  for (std::size_t p = 0; p < heights.size(); ++p) {
    const auto row = static_cast<Eigen::Index>(p / w), col = static_cast<Eigen::Index>(p % w);
    height_plane(row, col) = heights[p];
    for (std::size_t k = 0; k < 3; ++k) tone[k](row, col) = tones[k][p];
  }
  // The enlarged heights' own cast shadows, as the render pass draws them (edges repeated as here).
  const std::vector<float> horizons = range_map_horizons(height_plane, material.range.shadow_scale);
  SubspaceFidelity result;
  for (std::size_t s = 0; s < measured.size() && s < images.images.size(); ++s) {
    if (images.images[s].empty() || material.subspaces[s].channels != 3) continue;
    const MaterialDirection& l = material.lights[material.subspaces[s].light];
    const std::array<double, 3> light{std::sin(l.theta) * std::cos(l.phi),
                                      std::sin(l.theta) * std::sin(l.phi), std::cos(l.theta)};
    const MaterialDirection& v = material.views[material.subspaces[s].view];
    const std::array<double, 3> view{std::sin(v.theta) * std::cos(v.phi), std::sin(v.theta) * std::sin(v.phi),
                                     std::cos(v.theta)};
    RgbField model{images.images[s], w, h};
    apply_relief(model.rgb,
                 weighted_tone(tone, material.subspaces[s].tone_weight, material.range.tone_chroma),
                 relit_factor(height_plane, light, relight_floor(material), horizons));
    if (material.range.specular_strength > 0.0f) {
      const Plane highlight = lobe_of({material.range.specular_strength, material.range.specular_gloss,
                                       material.range.specular_view_power},
                                      height_plane, light, view, horizons);
      for (std::size_t p = 0; p < model.rgb.size(); ++p)
        model.rgb[p] += static_cast<float>(
            highlight(static_cast<Eigen::Index>(p / 3 / w), static_cast<Eigen::Index>(p / 3 % w)));
    }
    const CalibratedFidelity f = calibrated_fidelity(model, measured[s]);
    result.mean_rel += f.rel;
    result.mean_gaussian_rel += f.gaussian_rel;
    result.worst_rel = result.pairs == 0 ? f.rel : std::max(result.worst_rel, f.rel);
    ++result.pairs;
  }
  if (result.pairs > 0) {
    result.mean_rel /= result.pairs;
    result.mean_gaussian_rel /= result.pairs;
  }
  return result;
}

}  // namespace carbtf
