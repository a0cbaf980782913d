// The compact BTF material: everything the runtime needs to synthesize and render a measured material
// (docs/design.md 1 and 4). Analysis fills it; the material file (material_file.hpp) stores it; synthesis
// and rendering read it. Plain data with no invariants beyond those validate_material() checks, so it
// is cheap to copy and safe to share between threads for reading.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "carbtf/engine/status.hpp"

namespace carbtf {

// A measured direction on the upper hemisphere, in radians: theta from the surface normal, phi from +x
// towards +y (image up).
struct MaterialDirection {
  float theta = 0.0f;
  float phi = 0.0f;
  bool operator==(const MaterialDirection&) const = default;
};

// One causal neighbour of a 2D CAR model: the value at (row + dr, col + dc) feeds (row, col). Causal
// means dr < 0, or dr == 0 and dc < 0 (a non-symmetric half-plane).
struct CarNeighbour {
  std::int8_t dr = 0;
  std::int8_t dc = 0;
  bool operator==(const CarNeighbour&) const = default;
};

// Why a band's model differs from the plain Bayesian estimate; the analysis log says the same in words.
enum CarBandFlags : std::uint32_t {
  car_band_repaired = 1u << 0,     // the fitted recursion was unstable or near a unit root: gamma shrunk
  car_band_constant = 1u << 1,     // the band is constant: gamma empty, sigma 0
  car_band_white_noise = 1u << 2,  // too few samples for any neighbourhood: gamma empty
};

// One mono-spectral band of one pyramid level: Y(r) = mean + y(r), y(r) = sum_k gamma[k] y(r + n_k) +
// sigma e(r), e(r) ~ N(0, 1) (paper eq. 1).
struct CarBandModel {
  std::vector<CarNeighbour> neighbourhood;
  std::vector<float> gamma;  // one per neighbour, same order
  float sigma = 0.0f;        // noise standard deviation, in band units
  float mean = 0.0f;
  float band_std = 0.0f;    // standard deviation of the analysed band (for tolerances and reports)
  std::uint32_t flags = 0;  // CarBandFlags
  bool operator==(const CarBandModel&) const = default;
};

// The model of one subspace image (docs/design.md 4.3): colour = mean + transform * bands, where the bands
// are the collapse of a Gaussian-Laplacian pyramid of `levels` levels, each level holding `channels`
// CAR bands. bands[level * channels + channel]; level 0 is the finest.
struct SubspaceModel {
  std::uint32_t light = 0;  // the measured pair this subspace image is (nearest its cluster's centroid)
  std::uint32_t view = 0;
  std::uint32_t width = 0;  // size of the analysed image
  std::uint32_t height = 0;
  std::uint32_t channels = 3;
  std::uint32_t levels = 1;
  std::vector<float> colour_mean;  // channels, linear RGB (or spectral) mean
  std::vector<float>
      colour_transform;  // channels x channels, row-major: colour[i] = mean[i] + sum_j T[i][j] band[j]
  std::vector<CarBandModel> bands;  // levels * channels
  // How much of the relief tone this subspace image takes, in [0, 1]: the render multiplies it by
  // 1 + tone_weight * (tone - 1). The analysis chooses it per subspace by the texture measure, since
  // the tone (the crease darkening of the photometric-stereo view) helps some lights and views and
  // doubles shading the image already holds under others. 1 when the material has no tone.
  float tone_weight = 1.0f;
  bool operator==(const SubspaceModel&) const = default;
};

// The range (height) map, enlarged by Wang tiles (Cohen et al. 2003): every horizontal tile edge has
// one of `edge_colours` colours and so has every vertical edge, and there is one tile per combination
// of (north, east, south, west) colours. Each edge colour owns a source patch of tile_size^2 texels;
// a tile is the four patches of its edges, joined along minimum-error cuts that run from each corner
// to the centre (range_tiles.hpp builds the tiles and lays them out).
inline constexpr std::uint32_t kDefaultReliefChromaLevels = 1;
inline constexpr std::uint32_t kMaxReliefChromaLevels = 4;

struct RangeTiles {
  std::uint32_t tile_size = 0;     // even, texels
  std::uint32_t edge_colours = 2;  // per direction; patches = 2 * edge_colours, tiles = edge_colours^4
  float height_offset = 0.0f;      // height = offset + scale * quantized, in texel units
  float height_scale = 0.0f;
  // Source patches, row-major tile_size^2 each: horizontal-edge colours first, then vertical-edge ones.
  std::vector<std::uint16_t> patches;
  // Per tile and per quadrant (top-left, top-right, bottom-right, bottom-left), tile_size / 2 cut
  // positions: see range_tiles.hpp for their meaning.
  std::vector<std::uint16_t> cuts;
  // Relief tone (optional; empty means 1 everywhere): per texel of every patch, under the same layout
  // and cuts as the heights, a factor on the smooth texture's colour that follows the relief (dark
  // creases, bright ridges: albedo and occlusion the relit range map cannot give). The analysis divides
  // it out of the subspace images before their fit and the render pass multiplies it back, so the CAR
  // models only the smooth remainder. tone = tone_offset + tone_scale * quantized, mean about 1.
  // One plane (a grey tone) or three (linear R, G, B, plane-major, each patches.size()): a fabric whose
  // dark threads are blue and bright ones white has a tone of its own per channel, per texel.
  float tone_offset = 0.0f;
  float tone_scale = 0.0f;
  std::vector<std::uint8_t> tone;  // empty, patches.size() or 3 * patches.size()
  // How far each colour channel (linear R, G, B) follows the tone: channel c takes
  // 1 + tone_chroma[c] * (tone_c - 1), at least 0, where tone_c is the channel's plane or the grey one.
  // All 1 (the default, and any file without a TCHR chunk), each channel takes its plane as it is. A
  // grey tone with slopes is the cheap form of colour that follows the relief, the planes the full one.
  std::array<float, 3> tone_chroma{1.0f, 1.0f, 1.0f};
  // Cuts cross-fade the two patches over the texels within `feather` of them (range_tiles.hpp), so a
  // join shows no step; the patches then hold their real values that far beyond each cut. 0 (any file
  // without an FTHR chunk): hard cuts.
  std::uint32_t feather = 0;
  // The relief casts shadows (relief_horizons.hpp) when this is above 0: the render pass hides a light
  // from a texel whose horizon, of the heights times this scale, rises above it, and the tone was
  // measured with the same shadows divided out. 0 (any file without an SHDW chunk): no cast shadows.
  // Above 0 only with range tiles (validate_material).
  float shadow_scale = 0.0f;
  // The relief's specular lobe (model/relief_specular.hpp): the render pass adds
  // specular_strength * max(N.L, 0) * max(N.H, 0)^specular_gloss, N the range map's normal, to the
  // colour, and the analysis takes it out of the images before their fit. 0 (any file without a SPEC
  // chunk): no lobe. Above 0 only with range tiles (validate_material).
  float specular_strength = 0.0f;
  float specular_gloss = 0.0f;
  // The lobe grows with the view's tilt as (1 / max(V.z, kSpecularViewFloor))^specular_view_power
  // (specular_view_gain()), V the unit view in the tangent frame: the facets finer than the range map
  // resolves that turn to the half vector cover more of the image as the view tilts (the 1 / N.V of a
  // microfacet lobe over the macro surface), and the range map resolves only part of the relief. The
  // strength is the lobe's at the top view. 0 (any file without an SPVW chunk): the same at every view.
  float specular_view_power = 0.0f;
  // How many mip levels above its brightness the render pass reads the relief's chroma: the relief's
  // facets and creases finer than 4 * 2^chroma_levels texels change the colour's brightness and not its
  // chroma, as in measured images whose colour has less resolution than their brightness (a JPEG's 4:2:0
  // chroma). The analysis sets it from the data (analysis/model/relief_chroma.hpp); any file without an RCHL
  // chunk means kDefaultReliefChromaLevels, as the render pass drew those files.
  std::uint32_t chroma_levels = kDefaultReliefChromaLevels;
  bool operator==(const RangeTiles&) const = default;
};

struct Material {
  std::vector<MaterialDirection> lights;
  std::vector<MaterialDirection> views;
  std::vector<std::uint8_t> subspace_index;  // lights.size() * views.size(), [light * views + view]
  std::vector<SubspaceModel> subspaces;
  RangeTiles range;
  // Per (light, view) pair and linear colour channel, a gain the render pass applies to the pair's
  // colour (pair_gain()), so that the mean colour of every measured pair is its measurement's although
  // its subspace image is the representative pair's: a subspace groups pairs of like texture whose means
  // still differ (an elevation's shading, a view's colour shift). Empty (any file without a PGAN chunk),
  // every gain is 1; else three planes (R, G, B) of lights * views codes, [c * pairs + light * views +
  // view], code q meaning 2^((q - kPairGainZero) / kPairGainStepsPerOctave).
  std::vector<std::uint8_t> pair_gains;
  // The analysis settings and provenance, as ordered (key, value) text pairs.
  std::vector<std::pair<std::string, std::string>> settings;
  bool operator==(const Material&) const = default;
};

// Limits a material must respect; they bound every allocation a reader makes for a hostile file.
inline constexpr std::uint32_t kMaxMaterialDirections = 4096;
inline constexpr std::uint32_t kMaxSubspaces = 256;
inline constexpr std::uint32_t kMaxChannels = 16;
inline constexpr std::uint32_t kMaxPyramidLevels = 8;
inline constexpr std::uint32_t kMaxNeighbours = 64;
inline constexpr int kMaxNeighbourReach = 16;
inline constexpr std::uint32_t kMaxImageSize = 1u << 16;
inline constexpr std::uint32_t kMaxTileSize = 1024;
inline constexpr std::uint32_t kMaxEdgeColours = 4;
// The widest cross-fade of a cut (RangeTiles::feather), in texels.
inline constexpr std::uint32_t kMaxFeather = 4;
// The largest RangeTiles::shadow_scale.
inline constexpr float kMaxShadowScale = 4.0f;
inline constexpr float kMaxSpecularStrength = 16.0f;  // in the images' linear units; measured 0.03-0.09
inline constexpr float kMaxSpecularGloss = 1024.0f;
inline constexpr float kMaxSpecularViewPower = 2.0f;
// The view's z below which the lobe grows no more (about 75.5 degrees, the widest measured views').
// CARBTF_SPECULAR_VIEW_FLOOR in carbtf_gpu_shared.h.
inline constexpr float kSpecularViewFloor = 0.25f;
inline constexpr std::uint32_t kMaxSettings = 256;
inline constexpr std::uint32_t kMaxSettingLength = 4096;
// Every model number (colour mean and transform, band mean, std, sigma, gamma, range heights in
// texels) lies within +-kMaxModelMagnitude: linear colour is of order 1, so this is far beyond any fit,
// and with the stability margin below it keeps every synthesized value finite in float32.
inline constexpr float kMaxModelMagnitude = 1e6f;
// A relief tone lies within [0, kMaxRangeTone]: a factor on colour, so a hostile file cannot scale the
// render by more than the colour magnitudes above allow.
inline constexpr float kMaxRangeTone = 16.0f;
// A channel's tone chroma lies within [-kMaxToneChroma, kMaxToneChroma], so a channel's tone stays
// below 1 + 4 * 15 and the colour bounded.
inline constexpr float kMaxToneChroma = 4.0f;

// Pair gain codes (Material::pair_gains): a gain of 2^((q - kPairGainZero) / kPairGainStepsPerOctave),
// from 1/4 to just under 4 in steps of 1.1%.
inline constexpr int kPairGainZero = 128;
inline constexpr int kPairGainStepsPerOctave = 64;

// How many planes the relief tone has: 0 (none), 1 (grey) or 3 (per colour channel).
inline std::size_t tone_planes(const RangeTiles& range) {
  return range.patches.empty() ? 0 : range.tone.size() / range.patches.size();
}

// The subspace index of (light, view); the caller keeps both in range.
inline std::uint32_t subspace_of(const Material& material, std::uint32_t light, std::uint32_t view) {
  return material.subspace_index[std::size_t{light} * material.views.size() + view];
}

// The specular lobe's gain at a view of tangent-frame z `view_z` for a view power `power`
// (RangeTiles::specular_view_power); the shaders' carbtf_specular_view_gain() is the same.
float specular_view_gain(float power, float view_z);

// The gain a pair gain code means.
float pair_gain_of_code(std::uint8_t code);
// The gain of (light, view) on colour channel c (0-2) as the material stores it: 1 without gains.
float pair_gain(const Material& material, std::uint32_t light, std::uint32_t view, std::uint32_t channel);

// The floor of the render pass's relit factor's denominator (carbtf_material_shade): the cosine of the
// material's largest measured light elevation, at least 1e-3. The analysis divides the same factor out
// when it de-shades (analysis/model/deshade.hpp).
float relight_floor(const Material& material);

// The ambient share of the render pass's relit factor:
//   relit = kReliefAmbient + (1 - kReliefAmbient) max(N . L, 0) / max(L.z, relight_floor) visibility,
// so that a facet turned from the light, or in the relief's cast shadow, keeps a tenth of a flat
// facet's brightness, as the light from the rest of the sky and from the walls around it gives it in
// a photograph; a flat, unshadowed facet stays at 1. Without it such texels drew black: the hard black
// patches of coast_sand_rocks at grazing light, where the measurement has soft dark shadows (issue 42,
// item 4c; docs/design.md 5.3). CARBTF_RELIEF_AMBIENT in carbtf_gpu_shared.h.
inline constexpr float kReliefAmbient = 0.1f;

// Checks that the material is safe to synthesize and render: sizes agree, indices are in range,
// neighbours are causal and within reach, every number is finite and within kMaxModelMagnitude,
// sigma >= 0, every CAR band is stable with the margin of car_stability.hpp (the analysis's own test),
// and each direction set can be triangulated (no two equal directions). The message names the first
// offending element: the subspace, level and band, and the rule.
Status validate_material(const Material& material);

}  // namespace carbtf
