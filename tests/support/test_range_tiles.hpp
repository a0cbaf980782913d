// Wang range tiles for engine tests, made without the analysis library (the engine tests build with
// CARBTF_BUILD_ANALYSIS=OFF): the patches are windows of one map at seeded random places, as the
// analysis cuts them, and every cut runs straight from the tile corner to its centre. The analysis
// chooses its places and cuts to hide the joins; what the engine does with tiles is the same for any
// valid ones, so these exercise it as well.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "carbtf/engine/material/range_tiles.hpp"

namespace carbtf::test {

struct WindowedTileOptions {
  std::uint32_t map_rows = 48, map_cols = 48;  // the map the windows are cut from
  std::uint32_t tile_size = 16;                // even, at most the map's smaller side
  std::uint32_t edge_colours = 2;
  std::uint32_t height_bits = 6;
  std::uint32_t tone_bits = 4;
  std::uint32_t feather = 0;  // RangeTiles::feather
  std::uint64_t seed = 1;
};

// `height(row, col)` over the map; `tone(row, col)` likewise, or empty for a material without one.
inline RangeTiles windowed_range_tiles(const std::function<double(std::uint32_t, std::uint32_t)>& height,
                                       const std::function<double(std::uint32_t, std::uint32_t)>& tone,
                                       const WindowedTileOptions& options = {}) {
  const std::uint32_t size = options.tile_size, half = size / 2;
  std::vector<double> heights, tones;
  for (std::uint32_t r = 0; r < options.map_rows; ++r) {
    for (std::uint32_t c = 0; c < options.map_cols; ++c) {
      heights.push_back(height(r, c));
      if (tone) tones.push_back(tone(r, c));
    }
  }
  // Values quantized to `bits` between the map's extremes: the offset and scale a material stores.
  const auto quantizer = [](const std::vector<double>& values, std::uint32_t bits, float& offset,
                            float& scale) {
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    const double top = static_cast<double>((1u << bits) - 1u);
    offset = static_cast<float>(*low);
    scale = static_cast<float>((*high - *low) / top);
    return
        [=](double v) { return scale > 0.0f ? std::clamp(std::round((v - offset) / scale), 0.0, top) : 0.0; };
  };
  RangeTiles tiles;
  tiles.tile_size = size;
  tiles.edge_colours = options.edge_colours;
  tiles.feather = options.feather;
  const auto height_level = quantizer(heights, options.height_bits, tiles.height_offset, tiles.height_scale);
  std::function<double(double)> tone_level;
  if (tone) tone_level = quantizer(tones, options.tone_bits, tiles.tone_offset, tiles.tone_scale);
  std::mt19937_64 random(options.seed);
  std::vector<PatchWindow> windows;
  for (std::uint32_t p = 0; p < 2 * options.edge_colours; ++p) {
    const PatchWindow at{static_cast<std::uint32_t>(random() % (options.map_rows - size + 1)),
                         static_cast<std::uint32_t>(random() % (options.map_cols - size + 1))};
    windows.push_back(at);
    for (std::uint32_t r = 0; r < size; ++r) {
      for (std::uint32_t c = 0; c < size; ++c) {
        const std::size_t texel = std::size_t{at.row + r} * options.map_cols + at.col + c;
        tiles.patches.push_back(static_cast<std::uint16_t>(height_level(heights[texel])));
        if (tone) tiles.tone.push_back(static_cast<std::uint8_t>(tone_level(tones[texel])));
      }
    }
  }
  // cut[0] = 0, cut[v] = v on the diagonal (at least 1, at most half - 1), cut[half - 1] = half.
  std::vector<std::uint16_t> cut(half);
  for (std::uint32_t v = 1; v < half; ++v)
    cut[v] = static_cast<std::uint16_t>(v + 1 == half ? half : std::min(v, half - 1));
  for (std::uint32_t q = 0; q < range_tile_count(tiles) * 4; ++q)
    tiles.cuts.insert(tiles.cuts.end(), cut.begin(), cut.end());
  fill_unseen_patch_texels(tiles, windows);
  return tiles;
}

}  // namespace carbtf::test
