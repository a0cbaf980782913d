// Choosing the range map's Wang tiling by how its enlargement looks.
//
// The tiles' patches are drawn at seeded random places (range_tile_builder.hpp), and which places
// matters: on coast_sand_rocks one draw of four patches laid a long ridge across its tiles, a line of
// cast shadow at grazing light that the sample does not have, and another draw of the same map scored
// 0.189 / 0.361 against 0.078 / 0.203 (mean s, five pairs / spread16, docs/design.md 5.3). So the
// analysis draws a few tilings and keeps the one whose enlarged relief (its tone times the relit
// heights, with their cast shadows, under a light 30 degrees from the top and four grazing ones) is
// nearest the whole map's relief under the same lights, by the texture measure
// (quality/texture_distributions.hpp). The comparison is of the relief alone against itself, so it
// judges what the tiling changes and nothing the subspace models do.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/analysis/range/range_tile_builder.hpp"

namespace carbtf {

// What the relief's look is rendered with: the render pass's relit floor and cast-shadow scale.
struct ReliefLook {
  double light_z_floor = 0.0;
  double shadow_scale = 0.0;
};

struct RangeTilingChoice {
  RangeTiles tiles;
  std::uint64_t seed = 0;         // the RangeTileOptions::seed that built `tiles`
  std::vector<double> distances;  // per candidate, in candidate order: the mean texture distance
  std::size_t chosen = 0;         // the index of the chosen candidate
};

// The seed of candidate `index` for base seed `seed`: candidate 0 is `seed` itself, so that one
// candidate gives the tiling build_range_tiles() gives for `options`.
std::uint64_t tiling_candidate_seed(std::uint64_t seed, std::uint32_t index);

// Builds `candidates` (>= 1) tilings of `heights` with `tone` (as build_range_tiles()), candidate i
// seeded tiling_candidate_seed(options.seed, i), and keeps the nearest as above (the first of equals).
// `threads` as parallel_for (0: every core). Throws as build_range_tiles(), or std::invalid_argument for
// no candidates.
RangeTilingChoice choose_range_tiling(const Plane& heights, const RangeTileOptions& options,
                                      std::span<const Plane> tone, const ReliefLook& look,
                                      std::uint32_t candidates, unsigned threads = 0);

}  // namespace carbtf
