// The range map's horizons, for the cast shadows of the relief (docs/design.md 4.6): per texel and
// per azimuth k of kReliefHorizonDirections (k * 45 degrees from +x, counter-clockwise, y towards
// row 0 as in relief_normals.hpp), the tangent of the highest elevation at which the heights within
// kReliefHorizonReach texels along that azimuth rise above the texel, at least 0, of the heights times
// RangeTiles::shadow_scale. A light whose elevation tangent is under the horizon at its azimuth is
// hidden by the relief. Computed from the heights when the range map is bound, never stored in a
// material file: the photometric stereo's heights are in texels, so are the distances.
//
// Without them the render pass lights a crease wall that faces the light as brightly as an open facet
// while the relief tone (an average over all lights) darkens it: the measured images show the
// opposite order, a lit wall then a shadowed crease, and the relief looked lit from the wrong side.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace carbtf {

inline constexpr std::uint32_t kReliefHorizonDirections = 8;
// Measured at 256^2 (fidelity seeds 1-3, penumbra 0.25): a reach of 8 and of 24 texels score alike
// (coast_sand_rocks 0.228 and 0.226), and 8 costs a third.
inline constexpr std::uint32_t kReliefHorizonReach = 8;
// Visibility ramps from 0 to 1 as the light's elevation tangent passes the horizon -/+ half this:
// a penumbra, so that shadow edges do not alias and a light at the horizon is not all or nothing
// (CARBTF_RELIEF_SHADOW_SOFTNESS in carbtf_gpu_shared.h). Measured on coast_sand_rocks at 256^2 (mean
// rel, fidelity seeds 1-3): 1.0 gives 0.269, 0.25 0.228, 0.1 0.208, 0.05 0.200 (its sample renderer
// casts hard shadows); 0.1 keeps most of that and still a penumbra of about 6 degrees at 45.
inline constexpr float kReliefShadowSoftness = 0.1f;

// width * height heights (texel units, row-major) -> width * height * kReliefHorizonDirections
// horizon tangents of the heights times `scale`, the edge texels repeated or, for periodic textures,
// the addresses wrapped.
void relief_horizons(std::span<const float> heights, std::uint32_t width, std::uint32_t height, bool wrap,
                     float scale, std::vector<float>& out);

// Azimuths 4 * half to 4 * half + 3 of `horizons` (width * height * kReliefHorizonDirections, or empty
// for none) as `texels` RGBA texels: the range texture's layer 2 + half, zeros without horizons.
void horizon_layer(std::span<const float> horizons, std::size_t texels, std::uint32_t half,
                   std::vector<float>& out);

// The share of a directional light (tangent frame, z up, need not be unit) that the relief leaves
// on a texel of the given horizons: 1 above the horizon at the light's azimuth (interpolated between
// the two nearest directions), 0 below, a linear ramp of width kReliefShadowSoftness between.
// carbtf_relief_visibility() in carbtf_material.glsl computes the same.
float relief_visibility(std::span<const float, kReliefHorizonDirections> horizons,
                        const std::array<float, 3>& light);

}  // namespace carbtf
