#include "carbtf/engine/material/range_tiles.hpp"

#include <carbtf_gpu_shared.h>
#include <carbtf_periodic.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "material/raster_prediction.hpp"

namespace carbtf {
namespace {

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

// The tile at (tile_row, tile_col); with periods > 0 the tile grid repeats every `rows` x `cols` tiles
// (edge colours taken at the wrapped coordinates, so the last tile's far edge is the first one's near edge).
std::uint32_t tile_at(const RangeTiles& tiles, std::uint64_t seed, std::int64_t tile_row,
                      std::int64_t tile_col, std::int64_t rows, std::int64_t cols) {
  auto wrap = [](std::int64_t i, std::int64_t period) {
    return static_cast<std::uint32_t>(period > 0 ? i - floor_div(i, period) * period : i);
  };
  const auto lo = static_cast<std::uint32_t>(seed);
  const auto hi = static_cast<std::uint32_t>(seed >> 32);
  const std::uint32_t c = tiles.edge_colours;
  TileEdgeColours colours;
  colours.north = gpu::carbtf_tile_edge_colour(lo, hi, 0u, wrap(tile_row, rows), wrap(tile_col, cols), c);
  colours.south = gpu::carbtf_tile_edge_colour(lo, hi, 0u, wrap(tile_row + 1, rows), wrap(tile_col, cols), c);
  colours.west = gpu::carbtf_tile_edge_colour(lo, hi, 1u, wrap(tile_row, rows), wrap(tile_col, cols), c);
  colours.east = gpu::carbtf_tile_edge_colour(lo, hi, 1u, wrap(tile_row, rows), wrap(tile_col + 1, cols), c);
  return range_tile_index(tiles, colours);
}

// The block of the enlarged map, the tile grid repeating every rows x cols tiles where those are > 0.
void compose_block(const RangeTiles& tiles, const TextureWindow& block, std::int64_t rows, std::int64_t cols,
                   std::span<float> out, RangeChannel channel) {
  const std::uint32_t size = tiles.tile_size;
  const std::size_t texels = std::size_t{size} * size;
  std::vector<float> composed(texels * range_tile_count(tiles));
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    compose_range_tile(tiles, t, std::span<float>(composed).subspan(t * texels, texels), channel);
  }
  for (std::uint32_t r = 0; r < block.height; ++r) {
    const std::int64_t row = block.row0 + r;
    const std::int64_t tile_row = floor_div(row, size);
    const auto y = static_cast<std::size_t>(row - tile_row * size);
    for (std::uint32_t c = 0; c < block.width; ++c) {
      const std::int64_t col = block.col0 + c;
      const std::int64_t tile_col = floor_div(col, size);
      const auto x = static_cast<std::size_t>(col - tile_col * size);
      const std::uint32_t tile = tile_at(tiles, block.seed, tile_row, tile_col, rows, cols);
      out[std::size_t{r} * block.width + c] = composed[tile * texels + y * size + x];
    }
  }
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
    case TileQuadrant::top_left:
      return {colours.north, vertical_base + colours.west};
    case TileQuadrant::top_right:
      return {colours.north, vertical_base + colours.east};
    case TileQuadrant::bottom_right:
      return {colours.south, vertical_base + colours.east};
    case TileQuadrant::bottom_left:
      return {colours.south, vertical_base + colours.west};
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

// Calls texel(x, y, a, b, share_b) for every texel of `tile`: it shows (1 - share_b) of patch a and
// share_b of patch b, its quadrant's horizontal- and vertical-edge patches. share_b is the fraction of
// the (2 f + 1)^2 texels around it (within the quadrant; f = RangeTiles::feather) that lie on b's side
// of the cut: 0 or 1 away from the cut, a ramp across it. Two patches rarely agree exactly along their
// cut, and a hard step there shows as a line at grazing light (the normals take central differences);
// the ramp cross-fades the two real reliefs instead, and changes nothing where they agree.
template <typename Texel>
void for_each_tile_texel(const RangeTiles& tiles, std::uint32_t tile, Texel&& texel) {
  const std::uint32_t size = tiles.tile_size;
  const std::uint32_t half = size / 2;
  const std::int64_t feather = tiles.feather;
  const auto window_texels = static_cast<float>((2 * feather + 1) * (2 * feather + 1));
  for (std::uint32_t q = 0; q < 4; ++q) {
    const auto quadrant = static_cast<TileQuadrant>(q);
    const QuadrantPatches patches = quadrant_patches(tiles, tile, quadrant);
    const std::uint16_t* cut = tiles.cuts.data() + (std::size_t{tile} * 4 + q) * half;
    for (std::uint32_t v = 0; v < half; ++v) {
      for (std::uint32_t u = 0; u < half; ++u) {
        // Window texels on b's side (u' < cut[v']); texels beyond the quadrant count as the texel's own side.
        std::uint32_t on_b = 0;
        for (std::int64_t dv = -feather; dv <= feather; ++dv) {
          const std::int64_t row = std::clamp<std::int64_t>(std::int64_t{v} + dv, 0, half - 1);
          for (std::int64_t du = -feather; du <= feather; ++du) {
            const std::int64_t col = std::int64_t{u} + du;
            const bool inside = col >= 0 && col < std::int64_t{half};
            on_b += inside ? (col < cut[row]) : (u < cut[v]);
          }
        }
        std::uint32_t x = 0;
        std::uint32_t y = 0;
        quadrant_to_tile(size, quadrant, u, v, x, y);
        texel(x, y, patches.a, patches.b, static_cast<float>(on_b) / window_texels);
      }
    }
  }
}

}  // namespace

float patch_value_at_tile_texel(const RangeTiles& tiles, RangeChannel channel, std::uint32_t patch,
                                std::uint32_t x, std::uint32_t y) {
  const std::size_t texel = patch_texel(tiles, patch, x, y);
  if (channel != RangeChannel::height) {
    if (tiles.tone.empty()) return 1.0f;
    const std::size_t plane = tone_planes(tiles) == 3 ? static_cast<std::size_t>(channel) -
                                                            static_cast<std::size_t>(RangeChannel::tone)
                                                      : 0;
    return tiles.tone_offset +
           tiles.tone_scale * static_cast<float>(tiles.tone[plane * tiles.patches.size() + texel]);
  }
  return tiles.height_offset + tiles.height_scale * static_cast<float>(tiles.patches[texel]);
}

void compose_range_tile(const RangeTiles& tiles, std::uint32_t tile, std::span<float> out,
                        RangeChannel channel) {
  const std::uint32_t size = tiles.tile_size;
  for_each_tile_texel(
      tiles, tile, [&](std::uint32_t x, std::uint32_t y, std::uint32_t a, std::uint32_t b, float share_b) {
        const float from_a = share_b < 1.0f ? patch_value_at_tile_texel(tiles, channel, a, x, y) : 0.0f;
        const float from_b = share_b > 0.0f ? patch_value_at_tile_texel(tiles, channel, b, x, y) : 0.0f;
        out[std::size_t{y} * size + x] = share_b == 0.0f   ? from_a
                                         : share_b == 1.0f ? from_b
                                                           : from_a + share_b * (from_b - from_a);
      });
}

namespace {

// Which patch texels some tile shows, in full or in part.
std::vector<bool> shown_patch_texels(const RangeTiles& tiles) {
  std::vector<bool> shown(tiles.patches.size(), false);
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    for_each_tile_texel(
        tiles, t, [&](std::uint32_t x, std::uint32_t y, std::uint32_t a, std::uint32_t b, float share_b) {
          if (share_b < 1.0f) shown[patch_texel(tiles, a, x, y)] = true;
          if (share_b > 0.0f) shown[patch_texel(tiles, b, x, y)] = true;
        });
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
        tiles.patches[texel] = static_cast<std::uint16_t>(
            detail::raster_prediction(tiles.patches.data() + p * texels, size, x, y));
        for (std::size_t plane = 0; plane < tone_planes(tiles); ++plane) {
          std::uint8_t* tone = tiles.tone.data() + plane * tiles.patches.size();
          tone[texel] = static_cast<std::uint8_t>(detail::raster_prediction(tone + p * texels, size, x, y));
        }
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
  const std::size_t map_texels = std::size_t{rows} * cols, planes = tone_planes(tiles);
  std::vector<std::uint16_t> heights(map_texels);
  std::vector<std::uint8_t> tone(planes * map_texels);  // plane-major, as RangeTiles::tone
  std::vector<bool> shown(heights.size(), false);
  for (std::size_t p = 0; p < windows.size(); ++p) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t texel = p * texels + std::size_t{y} * size + x;
        if (!seen[texel]) continue;
        const std::size_t at = source_texel(p, x, y);
        shown[at] = true;
        heights[at] = tiles.patches[texel];
        for (std::size_t plane = 0; plane < planes; ++plane)
          tone[plane * map_texels + at] = tiles.tone[plane * tiles.patches.size() + texel];
      }
    }
  }
  for (std::uint32_t y = 0; y < rows; ++y) {
    for (std::uint32_t x = 0; x < cols; ++x) {
      const std::size_t at = std::size_t{y} * cols + x;
      if (shown[at]) continue;
      heights[at] = static_cast<std::uint16_t>(detail::raster_prediction(heights.data(), cols, x, y));
      for (std::size_t plane = 0; plane < planes; ++plane) {
        std::uint8_t* map = tone.data() + plane * map_texels;
        map[at] = static_cast<std::uint8_t>(detail::raster_prediction(map, cols, x, y));
      }
    }
  }
  for (std::size_t p = 0; p < windows.size(); ++p) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t texel = p * texels + std::size_t{y} * size + x;
        tiles.patches[texel] = heights[source_texel(p, x, y)];
        for (std::size_t plane = 0; plane < planes; ++plane) {
          tiles.tone[plane * tiles.patches.size() + texel] = tone[plane * map_texels + source_texel(p, x, y)];
        }
      }
    }
  }
}

JoinSteps measure_join_steps(const RangeTiles& tiles) {
  const std::uint32_t size = tiles.tile_size, half = size / 2;
  std::vector<float> tile(std::size_t{size} * size);
  double sum[2] = {0.0, 0.0};
  std::size_t count[2] = {0, 0};
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    compose_range_tile(tiles, t, tile);
    for (std::uint32_t q = 0; q < 4; ++q) {
      const auto quadrant = static_cast<TileQuadrant>(q);
      const std::uint16_t* cut = tiles.cuts.data() + (std::size_t{t} * 4 + q) * half;
      auto add = [&](std::uint32_t u0, std::uint32_t v0, std::uint32_t u1, std::uint32_t v1) {
        std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        quadrant_to_tile(size, quadrant, u0, v0, x0, y0);
        quadrant_to_tile(size, quadrant, u1, v1, x1, y1);
        const int across = (u0 < cut[v0]) != (u1 < cut[v1]) ? 0 : 1;
        sum[across] +=
            std::abs(double{tile[std::size_t{y0} * size + x0]} - tile[std::size_t{y1} * size + x1]);
        ++count[across];
      };
      for (std::uint32_t v = 0; v < half; ++v) {
        for (std::uint32_t u = 0; u < half; ++u) {
          if (u + 1 < half) add(u, v, u + 1, v);
          if (v + 1 < half) add(u, v, u, v + 1);
        }
      }
    }
  }
  return {count[0] ? sum[0] / static_cast<double>(count[0]) : 0.0,
          count[1] ? sum[1] / static_cast<double>(count[1]) : 0.0};
}

std::uint32_t range_tile_at(const RangeTiles& tiles, std::uint64_t seed, std::int32_t tile_row,
                            std::int32_t tile_col) {
  return tile_at(tiles, seed, tile_row, tile_col, 0, 0);
}

void enlarge_range_map(const RangeTiles& tiles, const TextureWindow& block, std::span<float> out,
                       RangeChannel channel) {
  const std::uint32_t size = tiles.tile_size, overlap = block.periodic_overlap;
  if (overlap == 0) {
    compose_block(tiles, block, 0, 0, out, channel);
  } else if (block.width % size == 0 && block.height % size == 0) {
    // Whole tiles per period: the tile grid itself repeats, so the relief stays whole across the wrap.
    compose_block(tiles, block, static_cast<std::int64_t>(block.height / size),
                  static_cast<std::int64_t>(block.width / size), out, channel);
  } else {
    // Otherwise the map folds as the subspace images do (carbtf_periodic.h), around its mean.
    TextureWindow grown = block;
    grown.width += overlap;
    grown.height += overlap;
    std::vector<float> whole(std::size_t{grown.width} * grown.height);
    compose_block(tiles, grown, 0, 0, whole, channel);
    double sum = 0.0;
    for (float v : whole) sum += v;
    const auto centre = static_cast<float>(sum / static_cast<double>(whole.size()));
    gpu::carbtf_fold_grid(whole, block.width, block.height, overlap, centre, out.data(), 1);
  }
}

}  // namespace carbtf
