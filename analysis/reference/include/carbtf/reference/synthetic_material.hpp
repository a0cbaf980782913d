// Materials built in code with known, stable CAR bands in the neighbourhood shapes the analysis fits:
// synthesis tests state exactly what they synthesize, and `carbtf bench synth` sweeps neighbourhood
// size, pyramid levels and subspace count independently of any measurement.
#pragma once

#include <cstdint>
#include <vector>

#include "carbtf/engine/material/material.hpp"

namespace carbtf {

// The 12-neighbour causal neighbourhood (reach 2 rows up, |dc| <= 2), the largest the analysis fits.
inline std::vector<CarNeighbour> wide_neighbourhood() {
  return {{0, -1}, {0, -2},  {-1, -2}, {-1, -1}, {-1, 0}, {-1, 1},
          {-1, 2}, {-2, -2}, {-2, -1}, {-2, 0},  {-2, 1}, {-2, 2}};
}

// A band with `neighbourhood` and gammas spread so that sum |gamma| = `total` (stable when < 1).
inline CarBandModel spread_band(std::vector<CarNeighbour> neighbourhood, float total, float sigma,
                                float mean) {
  CarBandModel band;
  band.neighbourhood = std::move(neighbourhood);
  const float each = total / static_cast<float>(band.neighbourhood.size());
  for (std::size_t k = 0; k < band.neighbourhood.size(); ++k) band.gamma.push_back(k % 3 == 2 ? -each : each);
  band.sigma = sigma;
  band.mean = mean;
  band.band_std = sigma;
  return band;
}

// The causal neighbourhoods of 1, 2, 4, 6 and 12 neighbours.
inline std::vector<std::vector<CarNeighbour>> neighbourhood_shapes() {
  return {{{-1, 0}},
          {{0, -1}, {-1, 0}},
          {{0, -1}, {-1, -1}, {-1, 0}, {-1, 1}},
          {{0, -1}, {0, -2}, {-1, -1}, {-1, 0}, {-1, 1}, {-2, 0}},
          wide_neighbourhood()};
}

// `subspaces` subspace images over a 7-direction set, `levels` pyramid levels, `channels` channels.
// Band neighbourhoods cycle through neighbourhood_shapes() so that every tap count is exercised, or all
// have `neighbours` neighbours when that names one of the shapes' sizes.
inline Material synthetic_material(std::uint32_t subspaces, std::uint32_t levels, std::uint32_t channels = 3,
                                   std::uint32_t neighbours = 0) {
  Material m;
  m.lights = {{0.0f, 0.0f}, {0.6f, 0.0f}, {0.6f, 2.1f}, {0.6f, 4.2f},
              {1.2f, 1.0f}, {1.2f, 3.1f}, {1.2f, 5.2f}};
  m.views = m.lights;
  std::vector<std::vector<CarNeighbour>> shapes = neighbourhood_shapes();
  for (const auto& candidate : neighbourhood_shapes()) {
    if (candidate.size() == neighbours) shapes = {candidate};
  }
  for (std::size_t i = 0; i < m.lights.size() * m.views.size(); ++i)
    m.subspace_index.push_back(static_cast<std::uint8_t>(i % subspaces));
  std::uint32_t shape = 0;
  for (std::uint32_t s = 0; s < subspaces; ++s) {
    SubspaceModel model;
    model.light = s % 7;
    model.view = s % 7;
    model.width = model.height = 64;
    model.channels = channels;
    model.levels = levels;
    for (std::uint32_t i = 0; i < channels; ++i) {
      model.colour_mean.push_back(0.1f + 0.2f * static_cast<float>(i) + 0.01f * static_cast<float>(s));
      for (std::uint32_t j = 0; j < channels; ++j) {
        model.colour_transform.push_back(
            i == j ? 0.8f : 0.3f / static_cast<float>(1 + i + j) * (j % 2 ? -1.0f : 1.0f));
      }
    }
    for (std::uint32_t level = 0; level < levels; ++level) {
      for (std::uint32_t c = 0; c < channels; ++c) {
        const float total = 0.55f + 0.1f * static_cast<float>((shape + level) % 4);
        model.bands.push_back(spread_band(shapes[shape++ % shapes.size()], total,
                                          0.05f + 0.02f * static_cast<float>(level),
                                          level == model.levels - 1 ? 0.01f * static_cast<float>(c) : 0.0f));
      }
    }
    m.subspaces.push_back(std::move(model));
  }
  return m;
}

}  // namespace carbtf
