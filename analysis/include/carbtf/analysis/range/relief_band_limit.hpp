// The relief's band limit: how sharp the render pass's normals of the range map are.
//
// The robust integration (surface_integration.hpp) gives heights whose central differences are
// photometric stereo's normals, noise and all, and the render pass draws every bit of it. The range map
// the model stores is half that map and half the map filtered by (-1 4 10 4 -1) / 16 on each axis
// (response (10 + 8 cos w - 2 cos 2w) / 16: 0.98 at 8 texels, 0.75 at 4, 0 at 2, the checkerboard that
// the central differences leave weakly tied). So a pattern along one axis keeps 0.5 + 0.5 x that
// response: 0.88 at 4 texels, 0.5 at 2.
// Measured (docs/design.md 5.2; 256^2, fidelity seeds 1-3, mean s five pairs / spread16):
//  - the filtered map alone took leather's crease walls to about 0.6 of the stereo's slope (leather 0.305
//    / 0.397, fabric 0.224 / 0.139, coast_sand_rocks 0.131 / 0.190);
//  - the map as integrated: 0.285 / 0.362, 0.232 / 0.133, 0.028 / 0.175 (fabric's five pairs further);
//  - half of each, this: 0.298 / 0.381, 0.217 / 0.136, 0.025 / 0.132, every mean nearer than the first.
#pragma once

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

// The share of the filtered map in the stored one.
inline constexpr double kReliefBandLimitShare = 0.5;

// `range_map` band-limited as above, treated as periodic (as the integration treats it).
Plane band_limit_relief(const Plane& range_map);

}  // namespace carbtf
