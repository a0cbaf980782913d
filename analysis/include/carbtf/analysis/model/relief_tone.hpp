// Colour that follows the relief (issue 13, item 3c): the relief tone.
//
// The render pass relights the range map, which gives the shading of each facet but not what makes a
// crease dark in a photograph: a darker albedo there, and the light its walls occlude and shadow. The
// relief tone is that remainder, measured on the photometric-stereo view under every light l:
//   tone(x) = sum_l I_l(x) / sum_l m_l relit_l(x),   m_l = mean I_l / mean relit_l
// (I_l the grey image, relit_l the render pass's relit factor of the range map, with its cast shadows
// where the material has them: model/relief_shadows.hpp), so that the render's
// own product relit * tone reproduces the view's brightness on average over the lights. It is stored
// under the range map's Wang layout, divided out of every subspace image before the CAR fit and
// multiplied back per fragment: the CAR then models the smooth remainder, and the creases darken where
// the range map puts them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/analysis/model/relief_specular.hpp"

namespace carbtf {

// Tones are kept within [kReliefToneFloor, kReliefToneCeiling]: dividing an image by a tone near
// zero would turn the noise of a shadowed crease into bright speckle.
inline constexpr double kReliefToneFloor = 0.1;
inline constexpr double kReliefToneCeiling = 4.0;

// The relief tone of `view` of `dataset` over `range_map` (heights in texels, the dataset's size),
// for the render pass's relit factor floor `light_z_floor`, with the cast shadows of `horizons` (none
// when empty), each image less the relief's specular `lobe` (model/relief_specular.hpp), which the
// render adds apart from the tone. Lights without an image are skipped; with none, the tone is 1
// everywhere.
Plane relief_tone(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map, double light_z_floor,
                  std::span<const float> horizons = {}, const SpecularLobe& lobe = {});

// The relief tone of each colour channel (linear R, G, B), the formula above on that channel's image:
// the tone's full colour, where a woven fabric's blue threads and white threads differ in hue, which
// one grey plane with a slope per channel (relief_tone_chroma) cannot draw.
std::vector<Plane> relief_tone_planes(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                                      double light_z_floor, std::span<const float> horizons = {},
                                      const SpecularLobe& lobe = {});

// How far the tone's colour departs from grey: the RMS over texels and channels of each channel's
// log tone minus the mean of the three. Requires three planes of one size.
double tone_colour_deviation(std::span<const Plane> planes);
// The colour deviation from which the analysis, asked to choose (AnalysisOptions::tone_planes), stores
// the tone's three planes rather than its grey plane. Measured at 256^2: fabric, blue and white
// threads, 0.266, and its mean rel (fidelity seeds 1-3) falls from 0.479 to 0.372 with the planes;
// leather 0.073 and coast_sand_rocks 0.067, whose mean rel rises with them (0.326 -> 0.336,
// 0.264 -> 0.278) and whose file grows by 23-24 KiB.
inline constexpr double kToneColourVisible = 0.15;

// A tone plane band-limited: filtered by the kernel [w, 1 - 2w, w], w = kToneBandLimitSide, along
// rows and then along columns (edges repeated). Per axis a period of 8 texels keeps 91% of its amplitude,
// of 4 texels 70%, of 2 texels 40%; the mean stays. Why: the tone is the measured images over the relit
// range map, and where the recovered heights miss a crease's depth (leather's narrowest creases by about
// a third) that ratio draws the crease as a one-texel dark line: grain that the measurement, whose creases
// are 3-4 texels of soft dark groove, lacks. The analysis keeps the band-limited tone where the subspace
// models look nearer with it (AnalysisOptions::tone_band_limit). A wider kernel ([1 2 1] / 4) took more of
// leather's grain, and the edges of coast_sand_rocks' rocks and grains with it (docs/design.md 5.3).
inline constexpr double kToneBandLimitSide = 0.15;
Plane band_limited_tone(const Plane& tone);

// Clamps every channel to its median +- k robust standard deviations (1.4826 x the median absolute
// deviation). After the tone is divided out, what remains outside that band is relief the tone does
// not explain at this pair's light and view (a cast shadow, a lit crease wall): thin lines that a CAR
// model, being Gaussian, can only reproduce as speckle all over the image. The tone and the range
// map draw the relief; the CAR keeps the smooth texture between.
void clamp_remainder(std::vector<Plane>& channels, double k);

// How far each colour channel follows the relief tone (RangeTiles::tone_chroma): the least-squares
// slope of the channel's own tone (the formula above on that channel) on the grey tone `tone`, within
// +-kMaxToneChroma. The slopes are kept only where they explain at least kToneChromaExplained of how
// the channels' own tones depart from the grey one, summed over the channels; otherwise all 1 (a grey
// tone). Measured at 256^2: fabric, whose threads are blue and white, 0.82 (its calibrated fidelity
// improves); leather 0.25 and coast_sand_rocks 0.32, where a coloured tone only adds chroma the
// measurement lacks (mean rel 0.334 -> 0.354 and 0.276 -> 0.293 with it).
inline constexpr double kToneChromaExplained = 0.5;
std::array<float, 3> relief_tone_chroma(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                                        double light_z_floor, const Plane& tone,
                                        std::span<const float> horizons = {}, const SpecularLobe& lobe = {});

// The tone per colour channel as a subspace image of tone weight `weight` takes it:
// max(1 + weight * chroma[c] * (tone_c - 1), 0), as the render pass composes it (SubspaceModel::tone_weight,
// RangeTiles::tone_chroma); tone_c is plane c of a three-plane tone, or the one plane of a grey tone.
// Throws std::invalid_argument for another plane count.
std::vector<Plane> weighted_tone(std::span<const Plane> tone, double weight,
                                 const std::array<float, 3>& chroma);

// The render pass's product for one measured pair, without parallax or direction interpolation:
// every pixel of `rgb` (interleaved RGB, row-major, the planes' size) times its channel's tone x relit
// (pass the subspace's weighted_tone()). What the analysis scores when it chooses the remainder clamp,
// and `bench synth` when it scores a synthesis.
void apply_relief(std::span<float> rgb, const std::vector<Plane>& tones, const Plane& relit);

// Scales the smooth texture so that the render pass's product keeps the measured image's mean. The
// CAR synthesizes the smooth texture independently of the relief, so the render's mean is
// sum_c mean(smooth_c) x mean(tone_c x relit), not the mean of the measured product, which the
// correlation between the measured remainder and the relief (and the remainder clamp) leaves
// elsewhere; the model was measured 4-7 sRGB steps darker than the measurement on every sample. One
// gain for all channels: per-channel gains were measured worse (they move the chroma of a material
// whose colour follows its relief). `measured` and `tones` have the channels' size; nothing changes
// where a mean is not positive.
void match_render_mean(std::vector<Plane>& smooth, const std::vector<Plane>& measured,
                       const std::vector<Plane>& tones, const Plane& relit);

}  // namespace carbtf
