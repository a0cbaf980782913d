// A de-shaded smooth texture (issue 13, item 3b; the second row of the paper's Fig. 8).
//
// The render pass multiplies the smooth BTF by the range map relit for the light,
//   relit(x) = max(N(x) . L, 0) / max(L.z, z_floor)     (compute_shaders/include/carbtf_material.glsl)
// with N from central differences of the range map. A measured subspace image already holds that
// shading, so fitting the CAR to it and rendering it relit applies the relief twice. Dividing the
// representative pair's relit factor out before fitting leaves the smooth part for the CAR model.
// Where the factor is small (self-shadowed facets) the division would amplify noise, so it is floored.
#pragma once

#include <array>
#include <vector>

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

// The render pass's relit factor at every texel of `range_map` (heights in texel units, row 0 at the
// top, borders mirrored), for the unit direction `light` towards the light in the tangent frame.
Plane relit_factor(const Plane& range_map, const std::array<double, 3>& light, double light_z_floor);

// Divides every channel by max(factor, floor); the channels and the factor share one size.
void divide_shading(std::vector<Plane>& channels, const Plane& factor, double floor);

}  // namespace carbtf
