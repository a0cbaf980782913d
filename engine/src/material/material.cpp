#include "carbtf/engine/material/material.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "carbtf/engine/material/car_stability.hpp"
#include "carbtf/engine/material/direction_interpolation.hpp"

namespace carbtf {
namespace {

Status invalid(const std::string& message) {
  return {ErrorCode::invalid_material, message};
}

std::string magnitude_text() {
  return std::to_string(static_cast<long long>(kMaxModelMagnitude));
}

bool finite(float value) {
  return std::isfinite(value);
}

bool bounded(float value) {
  return std::isfinite(value) && std::fabs(value) <= kMaxModelMagnitude;
}

bool all_bounded(const std::vector<float>& values) {
  for (float v : values) {
    if (!bounded(v)) return false;
  }
  return true;
}

Status validate_directions(const std::vector<MaterialDirection>& directions, const char* what) {
  if (directions.empty() || directions.size() > kMaxMaterialDirections) {
    return invalid(std::string(what) + " count " + std::to_string(directions.size()) + " is outside 1.." +
                   std::to_string(kMaxMaterialDirections));
  }
  constexpr float kHalfPi = 1.5707964f;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    const MaterialDirection& d = directions[i];
    if (!finite(d.theta) || !finite(d.phi) || d.theta < 0.0f || d.theta > kHalfPi) {
      return invalid(std::string(what) + " " + std::to_string(i) + " is not on the upper hemisphere");
    }
  }
  // The render pass interpolates over this triangulation: a set it cannot triangulate (two equal
  // directions, all on one great circle) is refused here rather than at the first frame.
  DirectionTriangulation triangulation;
  if (Status s = build_direction_triangulation(directions, triangulation); !s.ok())
    return invalid(std::string(what) + "s: " + s.message());
  return {};
}

Status validate_band(const CarBandModel& band, const std::string& where) {
  if (band.neighbourhood.size() > kMaxNeighbours)
    return invalid(where + " has more than " + std::to_string(kMaxNeighbours) + " neighbours");
  if (band.gamma.size() != band.neighbourhood.size())
    return invalid(where + " has " + std::to_string(band.gamma.size()) + " parameters for " +
                   std::to_string(band.neighbourhood.size()) + " neighbours");
  for (std::size_t k = 0; k < band.neighbourhood.size(); ++k) {
    const CarNeighbour n = band.neighbourhood[k];
    const bool causal = n.dr < 0 || (n.dr == 0 && n.dc < 0);
    if (!causal || n.dr < -kMaxNeighbourReach || n.dc < -kMaxNeighbourReach || n.dc > kMaxNeighbourReach) {
      return invalid(where + " neighbour " + std::to_string(k) + " (" + std::to_string(n.dr) + ", " +
                     std::to_string(n.dc) + ") is not causal within reach " +
                     std::to_string(kMaxNeighbourReach));
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (band.neighbourhood[j] == n)
        return invalid(where + " lists neighbour " + std::to_string(k) + " twice");
    }
  }
  if (!all_bounded(band.gamma) || !bounded(band.sigma) || !bounded(band.mean) || !bounded(band.band_std) ||
      band.sigma < 0.0f || band.band_std < 0.0f) {
    return invalid(where + " has a parameter that is not finite, negative or beyond +-" + magnitude_text());
  }
  const std::vector<double> gamma(band.gamma.begin(), band.gamma.end());
  if (!car_roots_within(band.neighbourhood, gamma, 1.0 - kCarStabilityMargin)) {
    return invalid(where + " is an unstable recursion: a characteristic root has modulus >= " +
                   std::to_string(1.0 - kCarStabilityMargin) + " (spectral radius " +
                   std::to_string(car_spectral_radius(band.neighbourhood, gamma)) +
                   "), so its synthesis would diverge");
  }
  return {};
}

Status validate_subspace(const SubspaceModel& s, std::size_t index, const Material& material) {
  const std::string where = "subspace " + std::to_string(index);
  if (s.light >= material.lights.size() || s.view >= material.views.size())
    return invalid(where + " names a direction pair out of range");
  if (s.width == 0 || s.height == 0 || s.width > kMaxImageSize || s.height > kMaxImageSize)
    return invalid(where + " has size " + std::to_string(s.width) + "x" + std::to_string(s.height));
  if (s.channels == 0 || s.channels > kMaxChannels)
    return invalid(where + " has " + std::to_string(s.channels) + " channels");
  if (s.levels == 0 || s.levels > kMaxPyramidLevels)
    return invalid(where + " has " + std::to_string(s.levels) + " pyramid levels");
  if (s.colour_mean.size() != s.channels || s.colour_transform.size() != std::size_t{s.channels} * s.channels)
    return invalid(where + " has a colour transform of the wrong size");
  if (!all_bounded(s.colour_mean) || !all_bounded(s.colour_transform))
    return invalid(where + " has a colour mean or transform entry that is not finite or beyond +-" +
                   magnitude_text());
  if (s.bands.size() != std::size_t{s.levels} * s.channels)
    return invalid(where + " has " + std::to_string(s.bands.size()) + " bands, not levels x channels");
  if (!(s.tone_weight >= 0.0f && s.tone_weight <= 1.0f))
    return invalid(where + " has tone weight " + std::to_string(s.tone_weight) + ", outside 0..1");
  for (std::size_t b = 0; b < s.bands.size(); ++b) {
    const std::string band =
        where + " level " + std::to_string(b / s.channels) + " band " + std::to_string(b % s.channels);
    if (Status status = validate_band(s.bands[b], band); !status.ok()) return status;
  }
  return {};
}

Status validate_range(const RangeTiles& r) {
  for (std::size_t channel = 0; channel < r.tone_chroma.size(); ++channel) {
    if (!(std::abs(r.tone_chroma[channel]) <= kMaxToneChroma)) {
      return invalid("range map: tone chroma " + std::to_string(channel) + " is " +
                     std::to_string(r.tone_chroma[channel]) + ", outside -" +
                     std::to_string(int(kMaxToneChroma)) + ".." + std::to_string(int(kMaxToneChroma)));
    }
  }
  if (!(r.shadow_scale >= 0.0f && r.shadow_scale <= kMaxShadowScale)) {
    return invalid("range map: shadow scale " + std::to_string(r.shadow_scale) + " is outside 0.." +
                   std::to_string(int(kMaxShadowScale)));
  }
  if (!(r.specular_strength >= 0.0f && r.specular_strength <= kMaxSpecularStrength)) {
    return invalid("range map: specular strength " + std::to_string(r.specular_strength) + " is outside 0.." +
                   std::to_string(int(kMaxSpecularStrength)));
  }
  if (r.specular_strength > 0.0f && !(r.specular_gloss >= 1.0f && r.specular_gloss <= kMaxSpecularGloss)) {
    return invalid("range map: specular gloss " + std::to_string(r.specular_gloss) + " is outside 1.." +
                   std::to_string(int(kMaxSpecularGloss)));
  }
  if (!(r.specular_view_power >= 0.0f && r.specular_view_power <= kMaxSpecularViewPower)) {
    return invalid("range map: specular view power " + std::to_string(r.specular_view_power) +
                   " is outside 0.." + std::to_string(int(kMaxSpecularViewPower)));
  }
  if (r.chroma_levels > kMaxReliefChromaLevels)
    return invalid("range map: the relief's chroma " + std::to_string(r.chroma_levels) +
                   " levels above its brightness (at most " + std::to_string(kMaxReliefChromaLevels) + ")");
  if (r.feather > kMaxFeather)
    return invalid("range map: feather " + std::to_string(r.feather) + " (at most " +
                   std::to_string(kMaxFeather) + ")");
  if (r.tile_size == 0) {
    if (!r.patches.empty() || !r.cuts.empty() || !r.tone.empty() || r.shadow_scale > 0.0f ||
        r.specular_strength > 0.0f || r.specular_view_power > 0.0f) {
      return invalid("range map: tile size 0 but tile data present");
    }
    return {};
  }
  if (r.tile_size % 2 != 0 || r.tile_size < 4 || r.tile_size > kMaxTileSize)
    return invalid("range map: tile size " + std::to_string(r.tile_size) + " is not even within 4.." +
                   std::to_string(kMaxTileSize));
  if (r.edge_colours == 0 || r.edge_colours > kMaxEdgeColours)
    return invalid("range map: " + std::to_string(r.edge_colours) + " edge colours");
  if (!bounded(r.height_offset) || !bounded(r.height_scale) ||
      std::fabs(r.height_offset) + 65535.0 * std::fabs(r.height_scale) > kMaxModelMagnitude) {
    return invalid("range map: heights (offset " + std::to_string(r.height_offset) + ", scale " +
                   std::to_string(r.height_scale) + ") are not finite or reach beyond +-" + magnitude_text() +
                   " texels");
  }
  const std::size_t texels = std::size_t{r.tile_size} * r.tile_size;
  const std::size_t c = r.edge_colours;
  if (r.patches.size() != 2 * c * texels) return invalid("range map: patch data has the wrong size");
  if (!r.tone.empty()) {
    if (r.tone.size() != r.patches.size() && r.tone.size() != 3 * r.patches.size()) {
      return invalid("range map: the relief tone has " + std::to_string(r.tone.size()) +
                     " texels, the patches " + std::to_string(r.patches.size()) +
                     " (it takes one plane or three)");
    }
    // The range the stored values reach (a tone quantized to fewer than 8 bits stays below 255).
    const auto [low_q, high_q] = std::minmax_element(r.tone.begin(), r.tone.end());
    const double lowest = std::min(r.tone_offset + double{r.tone_scale} * *low_q,
                                   r.tone_offset + double{r.tone_scale} * *high_q);
    const double highest = std::max(r.tone_offset + double{r.tone_scale} * *low_q,
                                    r.tone_offset + double{r.tone_scale} * *high_q);
    if (!std::isfinite(r.tone_offset) || !std::isfinite(r.tone_scale) || lowest < 0.0 ||
        highest > kMaxRangeTone) {
      return invalid("range map: the relief tone (offset " + std::to_string(r.tone_offset) + ", scale " +
                     std::to_string(r.tone_scale) + ") is not finite or leaves [0, " +
                     std::to_string(kMaxRangeTone) + "]");
    }
  }
  const std::size_t half = r.tile_size / 2;
  if (r.cuts.size() != c * c * c * c * 4 * half) return invalid("range map: cut data has the wrong size");
  for (std::size_t q = 0; q < r.cuts.size() / half; ++q) {
    const std::uint16_t* cut = r.cuts.data() + q * half;
    if (cut[0] != 0 || cut[half - 1] != half)
      return invalid("range map: cut " + std::to_string(q) + " does not run from corner to centre");
    for (std::size_t v = 1; v + 1 < half; ++v) {
      if (cut[v] < 1 || cut[v] > half - 1 || cut[v] < cut[v - 1])
        return invalid("range map: cut " + std::to_string(q) + " is not a monotone corner-to-centre path");
    }
  }
  return {};
}

}  // namespace

float pair_gain(const Material& material, std::uint32_t light, std::uint32_t view, std::uint32_t channel) {
  if (material.pair_gains.empty()) return 1.0f;
  const std::size_t pairs = material.lights.size() * material.views.size();
  return pair_gain_of_code(
      material.pair_gains[channel * pairs + std::size_t{light} * material.views.size() + view]);
}

float specular_view_gain(float power, float view_z) {
  if (power == 0.0f) return 1.0f;
  return std::pow(std::max(view_z, kSpecularViewFloor), -power);
}

float pair_gain_of_code(std::uint8_t code) {
  return std::exp2(static_cast<float>(int{code} - kPairGainZero) /
                   static_cast<float>(kPairGainStepsPerOctave));
}

float relight_floor(const Material& material) {
  float largest_theta = 0.0f;
  for (const auto& d : material.lights) largest_theta = std::max(largest_theta, d.theta);
  return std::max(std::cos(largest_theta), 1.0e-3f);
}

Status validate_material(const Material& material) {
  if (Status s = validate_directions(material.lights, "light direction"); !s.ok()) return s;
  if (Status s = validate_directions(material.views, "view direction"); !s.ok()) return s;
  if (material.subspaces.empty() || material.subspaces.size() > kMaxSubspaces) {
    return invalid("subspace count " + std::to_string(material.subspaces.size()) + " is outside 1.." +
                   std::to_string(kMaxSubspaces));
  }
  if (material.subspace_index.size() != material.lights.size() * material.views.size()) {
    return invalid("the subspace index table does not have lights x views entries");
  }
  for (std::size_t i = 0; i < material.subspace_index.size(); ++i) {
    if (material.subspace_index[i] >= material.subspaces.size()) {
      return invalid("subspace index entry " + std::to_string(i) + " names subspace " +
                     std::to_string(material.subspace_index[i]) + " of " +
                     std::to_string(material.subspaces.size()));
    }
  }
  for (std::size_t i = 0; i < material.subspaces.size(); ++i) {
    if (Status s = validate_subspace(material.subspaces[i], i, material); !s.ok()) return s;
  }
  if (Status s = validate_range(material.range); !s.ok()) return s;
  if (!material.pair_gains.empty()) {
    if (material.pair_gains.size() != 3 * material.subspace_index.size()) {
      return invalid("the pair gains are " + std::to_string(material.pair_gains.size()) +
                     " codes, not 3 x lights x views (" + std::to_string(3 * material.subspace_index.size()) +
                     ")");
    }
    for (std::size_t i = 0; i < material.subspaces.size(); ++i) {
      if (material.subspaces[i].channels != 3)
        return invalid("pair gains are RGB, but subspace " + std::to_string(i) + " has " +
                       std::to_string(material.subspaces[i].channels) + " channels");
    }
  }
  if (material.settings.size() > kMaxSettings)
    return invalid("more than " + std::to_string(kMaxSettings) + " settings");
  for (const auto& [key, value] : material.settings) {
    if (key.empty() || key.size() > kMaxSettingLength || value.size() > kMaxSettingLength)
      return invalid("a setting key or value is empty or too long");
  }
  return {};
}

}  // namespace carbtf
