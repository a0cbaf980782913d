// Building the Wang tiles that enlarge a range map (paper Sec. III, after Cohen et al. 2003; the
// geometry and layout rule are in engine/include/carbtf/engine/material/range_tiles.hpp). Each edge colour
// takes a source patch from the map at a seeded random position; each tile quadrant joins its two patches
// along the minimum-error cut, found by dynamic programming over monotone corner-to-centre paths with
// cost (A - B)^2 summed over the two texels either side of the cut.
#pragma once

#include <cstdint>
#include <span>

#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/engine/material/material.hpp"

namespace carbtf {

struct RangeTileOptions {
  // Clamped to the largest even size the map holds (at least 4). 128 rather than 64: each tile has
  // four corner-to-centre cuts, and at 64 texels they cross most cells of a 25-texel relief, drawing
  // crease fragments (calibrated fidelity, issue 13 note).
  std::uint32_t tile_size = 128;
  std::uint32_t edge_colours = 2;  // per direction, 1..4: 2 gives 16 tiles from 4 patches
  // Height quantization, 1..16 bits over the map's range. 6 bits leave a step of 1/63 of the range
  // (0.15 texel on leather's 9.4-texel relief, a fifth of its texel-to-texel slope). The calibrated
  // fidelity of the three samples at 256^2 is that of 8 bits to within 0.003 in the mean (leather
  // 0.334 -> 0.333, coast_sand_rocks 0.276 -> 0.271, fabric 0.457 -> 0.456); at 5 bits fabric's
  // grazing-light pair falls (0.551 -> 0.584), so 6 is the fewest that keep every sample.
  std::uint32_t height_bits = 6;
  // Relief-tone quantization, 1..8 bits over the tone's range (stored in u8): 4 scores as 7 does (a
  // step of 1/15 of the range, under the tone's own texel-to-texel noise), and 3 worsens leather.
  std::uint32_t tone_bits = 4;
  // The same for a tone of three colour planes, 1..8 bits: each plane's rounding is a colour error (the
  // levels are chosen together to keep the colour, tone_levels() in range_tile_builder.cpp, but a step
  // of 1/15 of the range still leaves speckle of every hue), which fabric's finest chroma octave showed
  // as grain: mean s at 256^2, seed 1, five pairs 0.453 at 4 bits, 0.307 at 5, 0.285 at 6 (32.9 KB
  // against 28.1), 0.281 at 7 (35.6 KB).
  std::uint32_t colour_tone_bits = 6;
  // Texels each cut cross-fades its two patches over (RangeTiles::feather), 0..4. 1 turns a join's
  // step into a 3-texel ramp: at 256^2 the mean height step across the cuts falls from 2.4 to 1.2 times
  // the relief's own on leather, and from 3.1 to 1.3 on coast_sand_rocks, and the mean structure score
  // s falls on every sample (docs/design.md 5.2); it adds 0.2-0.7 KB.
  std::uint32_t feather = 1;
  std::uint64_t seed = 1;
};

// Heights in texel units are quantized to height_bits over the map's range (stored in u16). `tone`
// (optional: none, one grey plane or three, R, G and B, each the map's size) is the relief tone
// (model/relief_tone.hpp): its patches are cut from the same places, so it stays aligned with the
// heights, and it is quantized to tone_bits over the range of all its planes (three planes: each channel
// rounded down or up, whichever keeps the texel's colour nearest). Patch texels that no tile
// shows are set to what the file's predictor expects (fill_unseen_patch_texels), so they cost nearly
// nothing in the file. Throws std::invalid_argument for a map smaller than 4 x 4, or a tone of another
// size or plane count.
RangeTiles build_range_tiles(const Plane& heights, const RangeTileOptions& options,
                             std::span<const Plane> tone = {});

}  // namespace carbtf
