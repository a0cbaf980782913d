// A de-shaded smooth texture (issue 13, item 3b; the second row of the paper's Fig. 8).
//
// The render pass multiplies the smooth BTF by the range map relit for the light,
//   relit(x) = a + (1 - a) max(N(x) . L, 0) / max(L.z, z_floor)
// (compute_shaders/include/carbtf_material.glsl; a = kReliefAmbient, carbtf/engine/material/material.hpp)
// with N from central differences of the range map. A measured subspace image already holds that
// shading, so fitting the CAR to it and rendering it relit applies the relief twice. Dividing the
// representative pair's relit factor out before fitting leaves the smooth part for the CAR model.
// Where the factor is small (self-shadowed facets) the division would amplify noise, so it is floored.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

// The render pass's relit factor at every texel of `range_map` (heights in texel units, row 0 at the
// top, borders mirrored), for the unit direction `light` towards the light in the tangent frame; with
// `horizons` (range_map_horizons() of model/relief_shadows.hpp), times the share of the light the
// relief's cast shadows leave, as the render pass of a material that casts shadows computes it.
Plane relit_factor(const Plane& range_map, const std::array<double, 3>& light, double light_z_floor,
                   std::span<const float> horizons = {});

// The facet of `range_map` at (row, col) as the render pass computes it: central differences, edges
// repeated, x along columns, y up (towards row - 1); its normal is (-dx, -dy, 1) / length. The relit
// factor and the specular lobe both light it.
struct RangeFacet {
  double dx = 0.0, dy = 0.0, length = 1.0;
  // The cosine between the facet's normal and the unit direction d.
  double cosine(const std::array<double, 3>& d) const { return (-dx * d[0] - dy * d[1] + d[2]) / length; }
};
RangeFacet range_map_facet(const Plane& range_map, Eigen::Index row, Eigen::Index col);

// The share of `light` the relief's cast shadows leave at texel `texel` (row-major) of the range map
// whose horizons (range_map_horizons()) these are; 1 without horizons.
double horizon_visibility(std::span<const float> horizons, Eigen::Index texel,
                          const std::array<double, 3>& light);

// Divides every channel by max(factor, floor); the channels and the factor share one size.
void divide_shading(std::vector<Plane>& channels, const Plane& factor, double floor);
// Divides channel c by max(factors[c], floor): one factor per channel (a coloured relief tone).
void divide_shading(std::vector<Plane>& channels, const std::vector<Plane>& factors, double floor);

// Undoes the render pass's parallax for a measured image seen from unit direction `view` (tangent
// frame): the render's ray march (carbtf_parallax_uv) shows at plane point u the texel u' its view ray
// meets first, u' = u + scale * h(u') * (view.x, -view.y) / view.z, so the material field that
// reproduces the image is W(u') = M(u' - scale * h(u') * (view.x, -view.y) / view.z), sampled
// bilinearly with edges clamped (view.z floored at kParallaxMinViewZ, as the march floors it): exact
// wherever no ridge hides u' from the view. The relief tone and the relit factor are defined on u', so
// an oblique image is brought there before either is divided out.
// The render pass's default parallax scale (MaterialBindingInfo::parallax_scale), which the analysis
// assumes when it undoes the parallax of a measured image.
inline constexpr double kAnalysisParallaxScale = 1.0;
void undo_parallax(std::vector<Plane>& channels, const Plane& range_map, const std::array<double, 3>& view,
                   double scale);

}  // namespace carbtf
