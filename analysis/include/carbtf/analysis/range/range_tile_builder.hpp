// Building the Wang tiles that enlarge a range map (paper Sec. III, after Cohen et al. 2003; the
// geometry and layout rule are in engine/include/carbtf/engine/range_tiles.hpp). Each edge colour takes
// a source patch from the map at a seeded random position; each tile quadrant joins its two patches
// along the minimum-error cut, found by dynamic programming over monotone corner-to-centre paths with
// cost (A - B)^2 summed over the two texels either side of the cut.
#pragma once

#include <cstdint>

#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/engine/material.hpp"

namespace carbtf {

struct RangeTileOptions {
  std::uint32_t tile_size = 64;     // clamped to the largest even size the map holds (at least 4)
  std::uint32_t edge_colours = 2;   // per direction, 1..4: 2 gives 16 tiles from 4 patches
  std::uint64_t seed = 1;
};

// Heights in texel units are quantized to 16 bits over the map's range. Throws std::invalid_argument
// for a map smaller than 4 x 4.
RangeTiles build_range_tiles(const Plane& heights, const RangeTileOptions& options);

}  // namespace carbtf
