// The range (height) map of a material, enlarged to any size from a few Wang tiles (RangeTiles in
// material.hpp). Tiles are composed on the CPU from the stored patches and cuts; the layout gives each
// tile edge a colour by hashing (seed, edge), so any block of the infinite map is computed on its own,
// without scanning from an origin, and the same seed always gives the same map. Two tiles that meet
// along an edge show the two halves of the same source patch there, so the map has no seams.
//
// Tile geometry (T = tile_size, h = T / 2; x = column, y = row within the tile):
//   north patch N (horizontal colour n): tile rows [0, h) show N[y + h][x]
//   south patch S:                       tile rows [h, T) show S[y - h][x]
//   west patch W (vertical colour w):    tile cols [0, h) show W[y][x + h]
//   east patch E:                        tile cols [h, T) show E[y][x - h]
// Each quadrant is shared by one horizontal-edge patch A (N or S) and one vertical-edge patch B (W or
// E). In quadrant-local coordinates (u from the tile's vertical edge inwards, v from its horizontal
// edge inwards, both in [0, h)), texel (u, v) shows B when u < cut[v] and A otherwise. Cuts are
// non-decreasing in v, cut[0] = 0 (the tile edge row is all A), cut[v] >= 1 for v >= 1 (the edge
// column is all B), cut[h - 1] = h, and cut[v] <= h - 1 below that, so a cut runs from the corner to
// the centre. Analysis picks each cut with minimum squared difference between A and B along it.
// Thread safety: all functions are pure.
#pragma once

#include <cstdint>
#include <span>

#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/material/texture_window.hpp"

namespace carbtf {

enum class TileQuadrant : std::uint32_t { top_left = 0, top_right = 1, bottom_right = 2, bottom_left = 3 };

struct TileEdgeColours {
  std::uint32_t north = 0, east = 0, south = 0, west = 0;
};

inline std::uint32_t range_tile_count(const RangeTiles& tiles) {
  const std::uint32_t c = tiles.edge_colours;
  return c * c * c * c;
}
inline std::uint32_t range_tile_index(const RangeTiles& tiles, TileEdgeColours colours) {
  const std::uint32_t c = tiles.edge_colours;
  return ((colours.north * c + colours.east) * c + colours.south) * c + colours.west;
}
TileEdgeColours range_tile_colours(const RangeTiles& tiles, std::uint32_t tile);

// The patch index (into RangeTiles::patches) of quadrant `quadrant` of `tile`: A is its
// horizontal-edge patch, B its vertical-edge patch.
struct QuadrantPatches {
  std::uint32_t a = 0, b = 0;
};
QuadrantPatches quadrant_patches(const RangeTiles& tiles, std::uint32_t tile, TileQuadrant quadrant);

// The tile texel (x, y) of quadrant-local (u, v).
inline void quadrant_to_tile(std::uint32_t tile_size, TileQuadrant quadrant, std::uint32_t u, std::uint32_t v,
                             std::uint32_t& x, std::uint32_t& y) {
  const bool right = quadrant == TileQuadrant::top_right || quadrant == TileQuadrant::bottom_right;
  const bool bottom = quadrant == TileQuadrant::bottom_right || quadrant == TileQuadrant::bottom_left;
  x = right ? tile_size - 1 - u : u;
  y = bottom ? tile_size - 1 - v : v;
}

// What a tile texel holds: the height (texel units), or the relief tone (a factor on colour, 1 where
// the material has none). All follow the same patches and cuts, so they stay aligned. `tone` is the
// grey tone or the red channel's; tone_green and tone_blue read their planes where the tone has three
// (material.hpp), and the grey tone where it has one.
enum class RangeChannel : std::uint32_t { height = 0, tone = 1, tone_green = 2, tone_blue = 3 };
// The tone channel of colour channel `k` (0 red, 1 green, 2 blue).
inline RangeChannel tone_channel(std::size_t k) {
  return static_cast<RangeChannel>(static_cast<std::uint32_t>(RangeChannel::tone) +
                                   static_cast<std::uint32_t>(k));
}

// The value patch `patch` shows at tile texel (x, y), following the geometry above; the caller
// passes a patch that covers (x, y).
float patch_value_at_tile_texel(const RangeTiles& tiles, RangeChannel channel, std::uint32_t patch,
                                std::uint32_t x, std::uint32_t y);
inline float patch_height_at_tile_texel(const RangeTiles& tiles, std::uint32_t patch, std::uint32_t x,
                                        std::uint32_t y) {
  return patch_value_at_tile_texel(tiles, RangeChannel::height, patch, x, y);
}

// Composes tile `tile` into `out` (tile_size^2 values, row-major).
void compose_range_tile(const RangeTiles& tiles, std::uint32_t tile, std::span<float> out,
                        RangeChannel channel = RangeChannel::height);

// Sets every patch texel that no tile shows (it lies beyond every cut that reaches it; about 40% of
// them) to the value the material file's raster filter predicts there, in heights and tone alike, so it
// costs almost nothing to store. Every composed tile stays the same. Requires valid tiles (cuts
// included).
void fill_unseen_patch_texels(RangeTiles& tiles);

// Where a patch was cut from its source map: the texel of the map at its top-left corner.
struct PatchWindow {
  std::uint32_t row = 0, col = 0;
};

// As above, for patches that are windows of one source map (`windows`, one per patch), as the analysis
// cuts them: texels the windows share hold one value, so the material file stores them once (its
// window filter). A texel one patch does not show takes the value another patch shows there; one no
// patch shows takes the raster filter's prediction over the source map, in its raster order. Requires
// that texels which several patches show agree in heights and tone, as windows of one map do.
void fill_unseen_patch_texels(RangeTiles& tiles, std::span<const PatchWindow> windows);

// The tile laid at tile coordinates (tile_row, tile_col) of the enlarged map for `seed`.
std::uint32_t range_tile_at(const RangeTiles& tiles, std::uint64_t seed, std::int32_t tile_row,
                            std::int32_t tile_col);

// How much a tile join steps: the mean absolute height difference between neighbouring texels of the
// composed tiles, over the pairs a cut separates and over the rest. A join shows as a line at grazing
// light when `across` is well above `elsewhere` (RangeTiles::feather ramps it). Requires tile_size > 0.
struct JoinSteps {
  double across = 0.0;
  double elsewhere = 0.0;
};
JoinSteps measure_join_steps(const RangeTiles& tiles);

// Writes a window of the enlarged map (texture_window.hpp) into `out` (width * height values of `channel`,
// row-major). Requires tile_size > 0. With periodic_overlap > 0 it tiles with period width x
// height, as a periodic synthesis of the subspace images does (docs/design.md 4.4): when the tile size
// divides both, the tile grid repeats (tile coordinates and edge colours wrap), so every relief cell
// stays whole; otherwise the map of (width + overlap) x (height + overlap) folds around its mean.
void enlarge_range_map(const RangeTiles& tiles, const TextureWindow& window, std::span<float> out,
                       RangeChannel channel = RangeChannel::height);

}  // namespace carbtf
