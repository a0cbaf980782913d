// The relief's band limit: how sharp the render pass's normals of the range map are.
//
// The robust integration (surface_integration.hpp) gives heights whose central differences are
// photometric stereo's normals, noise and all, and the render pass draws every bit of it. The
// measured images' relief is smoother: relit with the stereo normals as they are, coast_sand_rocks'
// fidelity falls from 0.197 / 0.433 to 0.315 / 0.586 (five pairs / spread16; docs/design.md 5.3). The
// range map the model stores is therefore band-limited by a fixed separable filter,
// (-1 4 10 4 -1) / 16 on each axis, of response (10 + 8 cos w - 2 cos 2w) / 16: 1 at long periods
// (0.98 at 8 texels), 0.75 at 4, 0.44 at 3 and 0 at 2, the checkerboard that the central differences
// leave weakly tied. A stronger one, (-1 8 18 8 -1) / 32 (0.63 at 4 texels), scored better on
// coast_sand_rocks and worse on leather.
#pragma once

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

// `range_map` filtered as above, treated as periodic (as the integration treats it).
Plane band_limit_relief(const Plane& range_map);

}  // namespace carbtf
