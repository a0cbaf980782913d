// The relief's specular lobe in the analysis (issue 13): a highlight that follows the range map.
//
// A measured image is not the relit relief times a smooth texture alone: a glossy surface adds a lobe
// where a facet's normal turns towards the half vector of light and view, on the thread tops and ridges
// the range map holds. The CAR, stationary, can only turn that relief-placed highlight into speckle.
// With the sample renderer's specular term left out of fabric, its mean rel falls from 0.353 to 0.208
// (tone planes, fidelity seeds 1-3 at 256^2), so the lobe is modelled on its own:
//   lobe(x) = strength * max(N(x) . L, 0) * max(N(x) . H, 0)^gloss,   H = normalize(L + V),
// N from the range map as the render pass computes it, in the images' linear units, grey. The strength
// and gloss are fitted to the photometric-stereo view's images together with the relit relief:
//   I_l = a_l relit_l tone + lobe_l,
// a_l per light, by least squares for each gloss of kSpecularGlosses, kept where it lowers the error of
// the relit relief alone (fit_shadow_scale's) by at least kSpecularFitGain.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

inline constexpr std::array<double, 7> kSpecularGlosses = {2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0};
inline constexpr double kSpecularFitGain = 0.02;
// The tone a lobe is fitted against still holds the highlights no lobe has yet taken out
// (fit_relief_specular_with_tone()).
inline constexpr int kSpecularToneRounds = 2;

// The lobe's growth with the view's tilt the analysis fits and stores (RangeTiles::specular_view_power):
// (1 / V.z)^0.5. Measured on leather at 256^2 (fidelity seeds 1-3, five / spread16, the lobe fitted
// without it and drawn at fidelity time with it): power 0 0.235 / 0.251, 0.5 0.228 / 0.238, 1 0.233 /
// 0.249; a strength x1.2 at every view instead 0.234 / 0.242, x1.4 0.244 / 0.242, each helping the
// 45-60 degree views and hurting the top ones (docs/design.md 5.2).
inline constexpr double kSpecularViewPower = 0.5;

// strength * max(N . L, 0) * max(N . H, 0)^gloss * specular_view_gain(view_power, V.z)
// (RangeTiles::specular_strength, _gloss and _view_power).
struct SpecularLobe {
  double strength = 0.0;  // 0: no lobe; the lobe's at the top view
  double gloss = 0.0;
  double view_power = 0.0;
};

struct SpecularFit {
  SpecularLobe lobe;
  double error = 0.0;          // the mean over lights of RMS(image - model) / mean image, with the lobe
  double error_without = 0.0;  // the same without it
};

// max(N . L, 0) * max(N . H, 0)^gloss at every texel of `range_map` (heights in texel units, edges
// repeated), for unit tangent-frame directions towards the light and the viewer; with `horizons`
// (range_map_horizons()), times the share of the light the relief's cast shadows leave.
Plane specular_lobe(const Plane& range_map, const std::array<double, 3>& light,
                    const std::array<double, 3>& view, double gloss, std::span<const float> horizons = {});

// specular_lobe() times the lobe's strength and its gain at `view`; all 0 without a lobe.
Plane lobe_of(const SpecularLobe& lobe, const Plane& range_map, const std::array<double, 3>& light,
              const std::array<double, 3>& view, std::span<const float> horizons = {});

// The lobe for the images of `view` of `dataset` over `range_map`, with the relief tone `tone` and the
// render pass's relit factor floor (see above). Throws std::invalid_argument when the sizes differ.
SpecularFit fit_relief_specular(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                                const Plane& tone, double light_z_floor,
                                std::span<const float> horizons = {});

// The lobe fitted in turn with the relief tone of `view`'s images: a texel where the lobe peaks under many
// lights looks like bright albedo, so a tone measured from the images as they are explains part of the
// lobe, and the lobe fitted against it falls short. The first fit is against that tone; each of
// kSpecularToneRounds more is against the tone of the images with the last fitted lobe taken out
// (relief_tone()'s lobe), and the rounds stop where a fit finds no lobe. Returns every round's fit,
// the first first; the last is the lobe. At 256^2 the stereo view's images are explained better on
// every round (error leather 0.2295 -> 0.2178 -> 0.2170, fabric 0.0962 -> 0.0897 -> 0.0888, their
// analysis logs). `horizons`: as fit_relief_specular's.
std::vector<SpecularFit> fit_relief_specular_with_tone(const BtfDataset& dataset, std::uint32_t view,
                                                       const Plane& range_map, double light_z_floor,
                                                       std::span<const float> horizons = {});

}  // namespace carbtf
