// The relief's cast shadows in the analysis (issue 13, item 3c): how strongly the range map shadows
// itself, fitted to the photometric-stereo view's images.
//
// The render pass relights the range map per facet. Without shadows a crease wall that faces the
// light stays as bright as an open facet, while the relief tone (an average over all lights) darkens
// it: a light from +x then drew the bright side of each crease on the wrong side (on leather at 45
// degrees, the x derivative's skewness came out +0.74 where the measurement's is -0.83). With the
// horizons of relief_horizons.hpp the render hides a light from texels the relief occludes, and the
// tone is measured with the same shadows divided out.
//
// How strongly: the recovered heights are not the true ones (photometric stereo makes creases
// shallower, and the integration adds slow tilts that shadow at grazing light), so the shadows are cast
// by the heights times a scale, chosen among kShadowScales by how well relit x shadow x tone explains
// every image of the view (the same layout, pixel for pixel), and kept only where that error falls by
// kShadowFitGain. Measured at 256^2 (penumbra 0.25), the error of scale 0 / 0.5 / 1: coast_sand_rocks
// 0.275 / 0.266 / 0.254 (shadows kept: mean rel 0.264 -> 0.208 at fidelity seeds 1-3 with the penumbra of
// 0.1); leather 0.313 / 0.312 / 0.345 and fabric 0.144 / 0.145 / 0.164 (none: with scale 1 leather's
// mean rel rose from 0.326 to 0.381).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

// The horizons of `range_map` (relief_horizons.hpp, edges repeated) for its heights times `scale`,
// kReliefHorizonDirections floats per texel, row-major; empty for scale 0 (no cast shadows).
std::vector<float> range_map_horizons(const Plane& range_map, double scale);

inline constexpr std::array<double, 3> kShadowScales = {0.0, 0.5, 1.0};
inline constexpr double kShadowFitGain = 0.02;
// The dark-sample rejection of the strict photometric stereo (AnalysisOptions::strict_stereo), as a
// fraction of the pixel's brightest sample: over the sample renderer's shadow floor (its ambient term,
// 0.03 of a flat facet's 0.8) with room for JPEG noise, under the dimmest lit facet worth a normal.
// On the leather sample at 256^2 the walls steeper than 65 degrees (69 on average) come out at 64
// instead of 49; its cells' median error is the same (0.73 degrees).
inline constexpr double kStrictStereoDarkFraction = 0.1;

struct ShadowFit {
  double scale = 0.0;          // the chosen RangeTiles::shadow_scale (0: no cast shadows)
  double error = 0.0;          // its error: the mean over lights of RMS(image - model) / mean image
  double error_without = 0.0;  // the error without cast shadows
};

// The shadow scale for the images of `view` of `dataset` over `range_map`, for the render pass's relit
// factor floor `light_z_floor` (see above). Throws std::invalid_argument when the range map is not the
// dataset's size.
ShadowFit fit_shadow_scale(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                           double light_z_floor);

}  // namespace carbtf
