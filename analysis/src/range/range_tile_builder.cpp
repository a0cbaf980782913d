#include "carbtf/analysis/range/range_tile_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "carbtf/engine/range_tiles.hpp"

namespace carbtf {
namespace {

// Minimum-error monotone cut for one quadrant: cut[0] = 0, cut[h - 1] = h, cut in [1, h - 1] between.
std::vector<std::uint16_t> best_cut(const RangeTiles& tiles, std::uint32_t tile, TileQuadrant quadrant) {
  const std::uint32_t half = tiles.tile_size / 2;
  const QuadrantPatches patches = quadrant_patches(tiles, tile, quadrant);
  auto error = [&](std::uint32_t u, std::uint32_t v) {
    std::uint32_t x = 0, y = 0;
    quadrant_to_tile(tiles.tile_size, quadrant, u, v, x, y);
    const double d = patch_height_at_tile_texel(tiles, patches.a, x, y) - patch_height_at_tile_texel(tiles, patches.b, x, y);
    return d * d;
  };
  std::vector<std::uint16_t> cut(half, 0);
  cut[half - 1] = static_cast<std::uint16_t>(half);
  if (half < 3) return cut;
  // cost[v][c] for v in [1, h - 2], c in [1, h - 1]; from[v][c] the c of row v - 1 it continues.
  const std::uint32_t rows = half - 2;
  std::vector<double> cost(std::size_t{rows} * half, std::numeric_limits<double>::infinity());
  std::vector<std::uint16_t> from(std::size_t{rows} * half, 0);
  for (std::uint32_t i = 0; i < rows; ++i) {
    const std::uint32_t v = i + 1;
    double best_before = std::numeric_limits<double>::infinity();
    std::uint16_t best_at = 1;
    for (std::uint32_t c = 1; c < half; ++c) {
      if (i > 0 && cost[(i - 1) * half + c] < best_before) {
        best_before = cost[(i - 1) * half + c];
        best_at = static_cast<std::uint16_t>(c);
      }
      const double here = error(c - 1, v) + error(c, v);
      cost[i * half + c] = here + (i == 0 ? 0.0 : best_before);
      from[i * half + c] = best_at;
    }
  }
  std::uint32_t c = 1;
  for (std::uint32_t k = 1; k < half; ++k) {
    if (cost[(rows - 1) * half + k] < cost[(rows - 1) * half + c]) c = k;
  }
  for (std::uint32_t i = rows; i-- > 0;) {
    cut[i + 1] = static_cast<std::uint16_t>(c);
    c = from[i * half + c];
  }
  return cut;
}

}  // namespace

RangeTiles build_range_tiles(const Plane& heights, const RangeTileOptions& options, const Plane* tone) {
  if (heights.rows() < 4 || heights.cols() < 4) throw std::invalid_argument("a range map needs at least 4 x 4 texels for tiles");
  if (tone != nullptr && (tone->rows() != heights.rows() || tone->cols() != heights.cols())) {
    throw std::invalid_argument("the relief tone is not the range map's size");
  }
  if (options.edge_colours == 0 || options.edge_colours > kMaxEdgeColours) throw std::invalid_argument("edge colours must be within 1..4");
  RangeTiles tiles;
  const auto largest = static_cast<std::uint32_t>(std::min(heights.rows(), heights.cols()));
  tiles.tile_size = std::max<std::uint32_t>(4, std::min({options.tile_size, largest, kMaxTileSize}) & ~1u);
  tiles.edge_colours = options.edge_colours;
  const double low = heights.minCoeff();
  const double high = heights.maxCoeff();
  tiles.height_offset = static_cast<float>(low);
  if (options.height_bits < 1 || options.height_bits > 16) throw std::invalid_argument("height bits must be within 1..16");
  const double top_level = static_cast<double>((1u << options.height_bits) - 1u);
  tiles.height_scale = static_cast<float>((high - low) / top_level);
  const std::uint32_t size = tiles.tile_size;
  std::mt19937_64 rng(options.seed);
  const std::uint32_t patch_count = 2 * tiles.edge_colours;
  tiles.patches.resize(std::size_t{patch_count} * size * size);
  double tone_low = 0.0;
  if (tone != nullptr) {
    tone_low = tone->minCoeff();
    tiles.tone_offset = static_cast<float>(tone_low);
    if (options.tone_bits < 1 || options.tone_bits > 8) throw std::invalid_argument("tone bits must be within 1..8");
    tiles.tone_scale = static_cast<float>((tone->maxCoeff() - tone_low) / static_cast<double>((1u << options.tone_bits) - 1u));
    tiles.tone.resize(tiles.patches.size());
  }
  for (std::uint32_t p = 0; p < patch_count; ++p) {
    const auto row0 = static_cast<Eigen::Index>(rng() % (static_cast<std::uint64_t>(heights.rows()) - size + 1));
    const auto col0 = static_cast<Eigen::Index>(rng() % (static_cast<std::uint64_t>(heights.cols()) - size + 1));
    for (std::uint32_t r = 0; r < size; ++r) {
      for (std::uint32_t c = 0; c < size; ++c) {
        const double h = heights(row0 + r, col0 + c);
        const double q = tiles.height_scale > 0.0f ? std::round((h - low) / tiles.height_scale) : 0.0;
        const std::size_t texel = (std::size_t{p} * size + r) * size + c;
        tiles.patches[texel] = static_cast<std::uint16_t>(std::clamp(q, 0.0, top_level));
        if (tone != nullptr) {
          const double t = tiles.tone_scale > 0.0f ? std::round(((*tone)(row0 + r, col0 + c) - tone_low) / tiles.tone_scale) : 0.0;
          tiles.tone[texel] = static_cast<std::uint8_t>(std::clamp(t, 0.0, static_cast<double>((1u << options.tone_bits) - 1u)));
        }
      }
    }
  }
  const std::uint32_t half = size / 2;
  tiles.cuts.resize(std::size_t{range_tile_count(tiles)} * 4 * half);
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    for (std::uint32_t q = 0; q < 4; ++q) {
      const auto cut = best_cut(tiles, t, static_cast<TileQuadrant>(q));
      std::copy(cut.begin(), cut.end(), tiles.cuts.begin() + static_cast<std::ptrdiff_t>((std::size_t{t} * 4 + q) * half));
    }
  }
  fill_unseen_patch_texels(tiles);
  return tiles;
}

}  // namespace carbtf
