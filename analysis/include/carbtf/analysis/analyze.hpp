// The whole analysis (docs/design.md 1): a measured BTF becomes a Material of tens of kilobytes.
// Stages: segmentation of the light x view space, photometric stereo on one view and its range map,
// Wang tiles of the range map, and per subspace image colour PCA, pyramid and one CAR model per band.
// Each stage's time and the process's peak RSS after it are recorded; anything repaired or unusual is
// reported through the log callback (and kept in the result).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/model/car_fit.hpp"
#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/analysis/range/photometric_stereo.hpp"
#include "carbtf/analysis/range/range_tile_builder.hpp"
#include "carbtf/analysis/segmentation/btf_segmentation.hpp"
#include "carbtf/engine/material/material.hpp"

namespace carbtf {

// An option the analysis can decide per material (automatic) or be told.
enum class AutoChoice { automatic, always, never };
using TonePlanes = AutoChoice;

// How much nearer the measurement (relative texture distance) another pyramid level count's model must
// be to replace AnalysisOptions::pyramid_levels for a subspace image. On leather at 256^2 the two
// counts' distances differ by 0.1-2% either way, one draw's noise; fabric's 2 levels are 4-13% nearer.
inline constexpr double kLevelChoiceMargin = 0.02;

// How much nearer the measurement the subspace models must be with the relief's specular lobe for an
// automatic lobe to stay. Set between the samples' margins, measured: fabric's models are 16% nearer
// with its lobe, leather's 1.7% (with the strict photometric stereo) and coast_sand_rocks' 0.6%; by
// the fidelity at 256^2 (seeds 1-3, five / spread16) the lobe takes leather from 0.440 / 0.558 to
// 0.386 / 0.550 and coast_sand_rocks from 0.189 / 0.361 to 0.281 / 0.448.
inline constexpr double kSpecularKeepMargin = 0.01;
// The same rule for the band-limited tone (AnalysisOptions::tone_band_limit): within 1%, the tone as
// measured stays.
inline constexpr double kToneBandLimitMargin = 0.01;

struct AnalysisOptions {
  SegmentationOptions segmentation;  // K, bins, seed
  std::uint32_t pyramid_levels = 3;  // 1..6 (fewer where the image is too small for them)
  CarFitOptions car;
  PhotometricStereoOptions stereo;
  int stereo_view = -1;  // -1: the view nearest the surface normal
  // Rescale sigma per level so that the collapsed pyramid keeps the measured contrast
  // (model/collapse_calibration.hpp). Off by default: it restores the variance, yet lowers the
  // calibrated fidelity on leather and coast_sand_rocks (issue 13 note).
  bool calibrate_collapse = false;
  // Store the relief tone (model/relief_tone.hpp) with the range tiles and divide it out of the
  // subspace images before their fit.
  bool relief_tone = true;
  // Each colour channel follows the tone by its own measured slope (RangeTiles::tone_chroma) where
  // those slopes explain the colour (model/relief_tone.hpp); off, the tone is grey. Opt-in: on fabric
  // at 256^2 it gives the threads their blue and white (mean rel 0.457 -> 0.415), but at 64^2 the
  // model's noise is then too strong (the same model with every sigma halved scores 0.470 against its
  // 0.506), which a fitted model must not be.
  bool coloured_tone = false;
  // Whether the relief tone gets a plane per colour channel (RangeTiles::tone, model/relief_tone.hpp),
  // so that colour follows the relief texel by texel; automatic: where the tone's colour departs from
  // grey by at least kToneColourVisible (fabric's blue and white threads; leather and coast_sand_rocks
  // keep one grey plane). On fabric at 256^2 it lowers the mean structure score s from 0.77 to 0.55
  // (docs/design.md 5.2); with the noise gains the fitted noise stays the measure's best.
  TonePlanes tone_planes = TonePlanes::automatic;
  // With the relief tone: whether the relief casts shadows (RangeTiles::shadow_scale,
  // model/relief_shadows.hpp); automatic: at the scale that best explains the photometric-stereo
  // view's images, where shadows explain them better (coast_sand_rocks at 256^2: mean rel 0.264 ->
  // 0.208; leather and fabric: none); always: at scale 1.
  AutoChoice relief_shadows = AutoChoice::automatic;
  // With the relief tone and automatic shadows: whether photometric stereo also rejects every sample
  // under kStrictStereoDarkFraction of the pixel's brightest (model/relief_shadows.hpp). Steep crease
  // walls see most lights in cast or attached shadow, and those samples pull their normals towards the
  // vertical (leather's 69-degree walls came out at 49). Automatic: that range map is kept where, with
  // its own cast shadows, it explains the photometric-stereo view's images better by kShadowFitGain
  // (leather and fabric at 256^2; coast_sand_rocks' relief is explained as well either way, and its
  // models look further with it). Never: PhotometricStereoOptions::dark_fraction alone.
  AutoChoice strict_stereo = AutoChoice::automatic;
  // With the relief tone: the smooth remainder is clamped to its median +- k robust standard
  // deviations before the fit (model/relief_tone.hpp; k = 0: not clamped). Per subspace, the k of
  // this list whose model image (CPU synthesis x tone x relit factor) is nearest the measured image
  // by the texture measure is kept: a woven material wants a tight clamp (its remainder
  // is relief the CAR can only turn into speckle), a stochastic one a loose one. Empty: no clamp.
  std::vector<double> remainder_clamps = {0.25, 0.5, 1.0, 1.5, 2.0, 3.0};
  // Noise draws (seeds seed, seed + 1, ...) each clamp candidate is synthesized from; it scores the
  // mean distance, so the choice follows the model more than one draw's noise. 1..16. Not above 1 by
  // default: 3 draws lowered fabric's mean rel at 256^2 (fidelity seeds 1-3) from 0.479 to 0.471 but
  // raised leather's from 0.326 to 0.328 and coast_sand_rocks' from 0.264 to 0.269.
  std::uint32_t selection_draws = 1;
  // With the relief tone: the candidate shares of the tone a subspace image takes (SubspaceModel::
  // tone_weight), chosen per subspace together with the clamp by the same measure. On
  // coast_sand_rocks the whole tone helps under low and grazing light yet doubles the shading the
  // image already holds at 45 degrees, and {0, 1} lowers its mean rel from 0.296 to 0.247 at 256^2.
  // Not the default: on leather the per-subspace choice does not predict the render (at 64^2 mean rel
  // 0.987 -> 1.149; at 256^2, of the 6 subspaces it changes, 3 score better and 3 worse). Empty or
  // {1}: the whole tone everywhere.
  std::vector<double> tone_weights = {1.0};
  // With the relief tone and a clamp list: the pyramid level counts (1..6) a subspace image may take
  // besides pyramid_levels (issue 13 item 3a), chosen per subspace with the clamp by the same measure.
  // One of them wins only where its model is nearer by kLevelChoiceMargin, so pyramid_levels stays
  // where the measure cannot tell them apart. {2} beside the default 3: on fabric at 256^2 most
  // subspaces take 2 levels and mean rel falls from 0.479 to 0.453 (fidelity seeds 1-3);
  // coast_sand_rocks 0.208 -> 0.201; leather keeps 3 everywhere, the same model. Empty: fixed.
  std::vector<std::uint32_t> other_level_counts = {2};
  // With the relief tone and a clamp list: after the clamp, tone weight and level count, the candidate
  // gains on the bands' sigma (the smooth texture's contrast around its mean), chosen per subspace by the
  // same measure, group after group (analyze.cpp, kGainGroups): the finest pyramid level's bands, its
  // chroma, the coarser levels' bands, their chroma (these two may also take noise_raises and
  // chroma_raises), then every band and the chroma bands. Where the tone and the relit range map already
  // draw what the image holds, the CAR's remainder is mostly the relief's misregistration, and at full
  // strength it puts speckle on leather's flat cells. Empty or {1}: the fitted sigma.
  std::vector<double> noise_gains = {1.0, 0.7, 0.5, 0.35, 0.25, 0.125, 0.0};
  // The coarser levels' raises: at 256^2 coast_sand_rocks' mean s over the five pairs, seed 1, went from
  // 0.694 (one gain for every level) to 0.276 with the gains per scale (docs/design.md 5.3). Empty or {1}:
  // none.
  std::vector<double> noise_raises = {1.0, 1.4, 2.0, 2.8};
  // The coarser levels' chroma raises, on top of their bands' gain. Wider than noise_raises: the CAR's
  // chroma at those levels is far weaker than leather's measured colour texture, and once the models are
  // scored as the render shows them the coarser levels' luma is lowered, chroma with it; at 2.8 the
  // chroma took the largest raise in most of leather's subspaces, and its mirror pair (45, 180) / (45, 0)
  // lost 4-8 dB of a* (docs/design.md 5.2). Empty or {1}: none.
  std::vector<double> chroma_raises = {1.0, 1.4, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0};
  // False: only the gains on every band and on the chroma bands, the model before the gains per scale.
  bool gains_per_scale = true;
  // Per measured pair, colour gains that give its render its measurement's mean Lab colour
  // (model/pair_gains.hpp, Material::pair_gains).
  bool pair_gains = true;
  // With the relief tone: fit the relief's specular lobe (model/relief_specular.hpp) to the
  // photometric-stereo view's images, where it explains them better; automatic: keep it where the
  // subspace models look nearer the measurement with it by kSpecularKeepMargin (docs/design.md 5.2 and
  // 5.3: leather's and fabric's sheen; since the models are scored as the render shows them,
  // coast_sand_rocks keeps it too, 1.7% nearer, where before it looked further with it). Either way the
  // lobe grows with the view's tilt where the models look nearer so (SpecularLobe::view_power; leather).
  // Always: keep it wherever fitted.
  AutoChoice relief_specular = AutoChoice::automatic;
  // With the relief tone: band-limit it (model/relief_tone.hpp, band_limited_tone); automatic: where the
  // subspace models, refitted over the band-limited tone (the tiling and the lobe as chosen before), look
  // nearer the measurement by kToneBandLimitMargin, at held-out draws. Measured at 256^2 (docs/design.md
  // 5.3): leather's and coast_sand_rocks' models look nearer with it, fabric's, whose threads the tone
  // draws texel by texel, further; fidelity seeds 1-3, five pairs / spread16, leather 0.356 / 0.511 ->
  // 0.345 / 0.465, coast_sand_rocks 0.151 / 0.308 -> 0.157 / 0.303 (flat).
  AutoChoice tone_band_limit = AutoChoice::automatic;
  double deshade_floor =
      0.0;  // > 0: divide the relit range map out before fitting, floored here (model/deshade.hpp)
  RangeTileOptions tiles;  // its seed is ignored: the first tiling drawn follows segmentation.seed
  // Range tilings drawn (range/range_tiling_choice.hpp), 1..64: the one whose enlarged relief looks most
  // like the whole map's is kept. Which places the patches come from moves the fidelity as much as a
  // model change: coast_sand_rocks' eight draws at 256^2 scored 0.05 to 0.26 (mean s, five pairs), and
  // the look's ranking put the best four first (docs/design.md 5.3). 1: the first draw, unscored.
  std::uint32_t tiling_candidates = 8;
  unsigned threads = 0;  // 0: all hardware threads
  bool progress = true;
};

struct StageReport {
  std::string name;
  double seconds = 0.0;
  std::size_t peak_rss_bytes = 0;  // of the process, after the stage
};

struct AnalysisResult {
  Material material;
  Segmentation segmentation;
  NormalMap normals;
  Plane range_map;                 // texel units, mean zero
  Plane tone;                      // the relief tone, grey (empty without it)
  std::vector<Plane> tone_planes;  // the stored tone's planes: none, the grey one, or R, G and B
  std::vector<float> horizons;     // the range map's horizons for its cast shadows (empty without)
  std::uint32_t stereo_view = 0;
  std::vector<StageReport> stages;
  std::vector<std::string> log;
};

// Throws std::invalid_argument for options out of range or a dataset the method cannot
// use (no images, fewer than 3 lights for the stereo view).
AnalysisResult analyze_btf(const BtfDataset& dataset, const AnalysisOptions& options,
                           const std::function<void(const std::string&)>& log = {});

}  // namespace carbtf
