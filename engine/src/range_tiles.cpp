#include "carbtf/engine/material/range_tiles.hpp"

#include <carbtf_gpu_shared.h>

#include <algorithm>
#include <vector>

#include "raster_prediction.hpp"

namespace carbtf {
namespace {

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

}  // namespace

TileEdgeColours range_tile_colours(const RangeTiles& tiles, std::uint32_t tile) {
  const std::uint32_t c = tiles.edge_colours;
  TileEdgeColours colours;
  colours.west = tile % c;
  tile /= c;
  colours.south = tile % c;
  tile /= c;
  colours.east = tile % c;
  colours.north = tile / c;
  return colours;
}

QuadrantPatches quadrant_patches(const RangeTiles& tiles, std::uint32_t tile, TileQuadrant quadrant) {
  const TileEdgeColours colours = range_tile_colours(tiles, tile);
  const std::uint32_t vertical_base = tiles.edge_colours;
  switch (quadrant) {
    case TileQuadrant::top_left: return {colours.north, vertical_base + colours.west};
    case TileQuadrant::top_right: return {colours.north, vertical_base + colours.east};
    case TileQuadrant::bottom_right: return {colours.south, vertical_base + colours.east};
    case TileQuadrant::bottom_left: return {colours.south, vertical_base + colours.west};
  }
  return {};
}

namespace {

// The index into RangeTiles::patches (or tone) of the texel `patch` shows at tile texel (x, y).
std::size_t patch_texel(const RangeTiles& tiles, std::uint32_t patch, std::uint32_t x, std::uint32_t y) {
  const std::uint32_t size = tiles.tile_size;
  const std::uint32_t half = size / 2;
  std::uint32_t row = y;
  std::uint32_t col = x;
  if (patch < tiles.edge_colours) {
    row = y < half ? y + half : y - half;  // the north role above the centre, the south role below
  } else {
    col = x < half ? x + half : x - half;  // the west role left of the centre, the east role right
  }
  return (std::size_t{patch} * size + row) * size + col;
}

// Calls shown(x, y, patch) for every texel of `tile` with the patch its cut gives it.
template <typename Shown>
void for_each_tile_texel(const RangeTiles& tiles, std::uint32_t tile, Shown&& shown) {
  const std::uint32_t size = tiles.tile_size;
  const std::uint32_t half = size / 2;
  for (std::uint32_t q = 0; q < 4; ++q) {
    const auto quadrant = static_cast<TileQuadrant>(q);
    const QuadrantPatches patches = quadrant_patches(tiles, tile, quadrant);
    const std::uint16_t* cut = tiles.cuts.data() + (std::size_t{tile} * 4 + q) * half;
    for (std::uint32_t v = 0; v < half; ++v) {
      for (std::uint32_t u = 0; u < half; ++u) {
        std::uint32_t x = 0;
        std::uint32_t y = 0;
        quadrant_to_tile(size, quadrant, u, v, x, y);
        shown(x, y, u < cut[v] ? patches.b : patches.a);
      }
    }
  }
}

}  // namespace

float patch_value_at_tile_texel(const RangeTiles& tiles, RangeChannel channel, std::uint32_t patch, std::uint32_t x,
                                std::uint32_t y) {
  const std::size_t texel = patch_texel(tiles, patch, x, y);
  if (channel == RangeChannel::tone) {
    return tiles.tone.empty() ? 1.0f : tiles.tone_offset + tiles.tone_scale * static_cast<float>(tiles.tone[texel]);
  }
  return tiles.height_offset + tiles.height_scale * static_cast<float>(tiles.patches[texel]);
}

void compose_range_tile(const RangeTiles& tiles, std::uint32_t tile, std::span<float> out, RangeChannel channel) {
  const std::uint32_t size = tiles.tile_size;
  for_each_tile_texel(tiles, tile, [&](std::uint32_t x, std::uint32_t y, std::uint32_t patch) {
    out[std::size_t{y} * size + x] = patch_value_at_tile_texel(tiles, channel, patch, x, y);
  });
}

namespace {

// Which patch texels some tile shows.
std::vector<bool> shown_patch_texels(const RangeTiles& tiles) {
  std::vector<bool> shown(tiles.patches.size(), false);
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    for_each_tile_texel(tiles, t, [&](std::uint32_t x, std::uint32_t y, std::uint32_t patch) { shown[patch_texel(tiles, patch, x, y)] = true; });
  }
  return shown;
}

}  // namespace

void fill_unseen_patch_texels(RangeTiles& tiles) {
  const std::uint32_t size = tiles.tile_size;
  if (size == 0) return;
  const std::vector<bool> seen = shown_patch_texels(tiles);
  // Raster order, so each prediction reads texels already final, as the file's decoder will.
  const std::size_t texels = std::size_t{size} * size;
  for (std::size_t p = 0; p * texels < tiles.patches.size(); ++p) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t texel = p * texels + std::size_t{y} * size + x;
        if (seen[texel]) continue;
        tiles.patches[texel] = static_cast<std::uint16_t>(detail::raster_prediction(tiles.patches.data() + p * texels, size, x, y));
        if (!tiles.tone.empty()) tiles.tone[texel] = static_cast<std::uint8_t>(detail::raster_prediction(tiles.tone.data() + p * texels, size, x, y));
      }
    }
  }
}

void fill_unseen_patch_texels(RangeTiles& tiles, std::span<const PatchWindow> windows) {
  const std::uint32_t size = tiles.tile_size;
  if (size == 0) return;
  const std::size_t texels = std::size_t{size} * size;
  if (windows.size() * texels != tiles.patches.size()) return fill_unseen_patch_texels(tiles);
  const std::vector<bool> seen = shown_patch_texels(tiles);
  std::uint32_t rows = 0, cols = 0;
  for (const PatchWindow& w : windows) {
    rows = std::max(rows, w.row + size);
    cols = std::max(cols, w.col + size);
  }
  const auto source_texel = [&](std::size_t patch, std::uint32_t x, std::uint32_t y) {
    return std::size_t{windows[patch].row + y} * cols + windows[patch].col + x;
  };
  std::vector<std::uint16_t> heights(std::size_t{rows} * cols);
  std::vector<std::uint8_t> tone(tiles.tone.empty() ? 0 : heights.size());
  std::vector<bool> shown(heights.size(), false);
  for (std::size_t p = 0; p < windows.size(); ++p) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t texel = p * texels + std::size_t{y} * size + x;
        if (!seen[texel]) continue;
        const std::size_t at = source_texel(p, x, y);
        shown[at] = true;
        heights[at] = tiles.patches[texel];
        if (!tone.empty()) tone[at] = tiles.tone[texel];
      }
    }
  }
  for (std::uint32_t y = 0; y < rows; ++y) {
    for (std::uint32_t x = 0; x < cols; ++x) {
      const std::size_t at = std::size_t{y} * cols + x;
      if (shown[at]) continue;
      heights[at] = static_cast<std::uint16_t>(detail::raster_prediction(heights.data(), cols, x, y));
      if (!tone.empty()) tone[at] = static_cast<std::uint8_t>(detail::raster_prediction(tone.data(), cols, x, y));
    }
  }
  for (std::size_t p = 0; p < windows.size(); ++p) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t texel = p * texels + std::size_t{y} * size + x;
        tiles.patches[texel] = heights[source_texel(p, x, y)];
        if (!tone.empty()) tiles.tone[texel] = tone[source_texel(p, x, y)];
      }
    }
  }
}

std::uint32_t range_tile_at(const RangeTiles& tiles, std::uint64_t seed, std::int32_t tile_row, std::int32_t tile_col) {
  const auto lo = static_cast<std::uint32_t>(seed);
  const auto hi = static_cast<std::uint32_t>(seed >> 32);
  const auto row = static_cast<std::uint32_t>(tile_row);
  const auto col = static_cast<std::uint32_t>(tile_col);
  const std::uint32_t c = tiles.edge_colours;
  TileEdgeColours colours;
  colours.north = gpu::carbtf_tile_edge_colour(lo, hi, 0u, row, col, c);
  colours.south = gpu::carbtf_tile_edge_colour(lo, hi, 0u, row + 1u, col, c);
  colours.west = gpu::carbtf_tile_edge_colour(lo, hi, 1u, row, col, c);
  colours.east = gpu::carbtf_tile_edge_colour(lo, hi, 1u, row, col + 1u, c);
  return range_tile_index(tiles, colours);
}

void enlarge_range_map(const RangeTiles& tiles, std::uint64_t seed, std::int64_t row0, std::int64_t col0,
                       std::uint32_t width, std::uint32_t height, std::span<float> out, RangeChannel channel) {
  const std::uint32_t size = tiles.tile_size;
  const std::size_t texels = std::size_t{size} * size;
  std::vector<float> composed(texels * range_tile_count(tiles));
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    compose_range_tile(tiles, t, std::span<float>(composed).subspan(t * texels, texels), channel);
  }
  for (std::uint32_t r = 0; r < height; ++r) {
    const std::int64_t row = row0 + r;
    const std::int64_t tile_row = floor_div(row, size);
    const auto y = static_cast<std::size_t>(row - tile_row * size);
    for (std::uint32_t c = 0; c < width; ++c) {
      const std::int64_t col = col0 + c;
      const std::int64_t tile_col = floor_div(col, size);
      const auto x = static_cast<std::size_t>(col - tile_col * size);
      const std::uint32_t tile = range_tile_at(tiles, seed, static_cast<std::int32_t>(tile_row), static_cast<std::int32_t>(tile_col));
      out[std::size_t{r} * width + c] = composed[tile * texels + y * size + x];
    }
  }
}

}  // namespace carbtf
