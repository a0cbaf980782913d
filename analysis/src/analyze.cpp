#include "carbtf/analysis/analyze.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "carbtf/analysis/model/collapse_calibration.hpp"
#include "carbtf/analysis/model/colour_pca.hpp"
#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/pair_gains.hpp"
#include "carbtf/analysis/model/parallax_view.hpp"
#include "carbtf/analysis/model/pyramid.hpp"
#include "carbtf/analysis/model/relief_chroma.hpp"
#include "carbtf/analysis/model/relief_shadows.hpp"
#include "carbtf/analysis/model/relief_specular.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/analysis/progress.hpp"
#include "carbtf/analysis/quality/texture_distributions.hpp"
#include "carbtf/analysis/range/range_tiling_choice.hpp"
#include "carbtf/analysis/range/surface_integration.hpp"
#include "carbtf/analysis/resource_usage.hpp"
#include "carbtf/reference/parallel_for.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"

namespace carbtf {
namespace {

class StageClock {
 public:
  StageClock(AnalysisResult& result, std::string name)
      : result_(result), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}
  ~StageClock() {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    result_.stages.push_back({name_, seconds, peak_rss_bytes()});
  }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;

 private:
  AnalysisResult& result_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
};

std::string join_numbers(const std::vector<double>& values) {
  std::ostringstream text;
  for (std::size_t i = 0; i < values.size(); ++i) text << (i ? "," : "") << values[i];
  return text.str();
}

// How the settings record names an automatic choice: `automatic` says where it is made, `always` what
// is forced.
const char* describe_choice(AutoChoice choice, const char* automatic, const char* always = "yes") {
  return choice == AutoChoice::automatic ? automatic : choice == AutoChoice::always ? always : "no";
}

// The range map the model stores for a normal map: robustly integrated, its central differences the
// stereo's slopes. Not band-limited: the (-1 4 10 4 -1) / 16 filter it once had took the creases' walls
// to about 0.6 of their slope, and without it the stereo view's images are explained better and every
// sample's fidelity improves but fabric's five pairs (docs/design.md 5.2).
Plane relief_of(const NormalMap& normals) {
  return integrate_normals(normals.normals, normals.width, normals.height);
}

// The share of a normal map's texels whose stereo fit had enough samples, in percent.
double valid_percent(const NormalMap& normals) {
  const auto valid = std::count(normals.valid.begin(), normals.valid.end(), 1);
  return 100.0 * static_cast<double>(valid) /
         static_cast<double>(std::max<std::size_t>(1, normals.valid.size()));
}

MaterialDirection to_material(const Direction& d) {
  return {static_cast<float>(d.theta), static_cast<float>(d.phi)};
}

// Significant bits kept of each colour and band number (mean, transform, band mean, std, sigma): a
// relative change of at most 2^-13, far below an 8-bit output step (2^-8) and the numbers' own
// estimation error, while the cleared low mantissa bits let the file deflate them (about 1 KB of a
// 256^2 material). Gammas are rounded by their own posterior error (car_fit.cpp).
constexpr int kStoredSignificantBits = 12;

float to_stored_precision(float value) {
  if (value == 0.0f || !std::isfinite(value)) return value;
  int exponent = 0;
  const double fraction = std::frexp(static_cast<double>(value),
                                     &exponent);  // value = fraction 2^exponent, |fraction| in [0.5, 1)
  return static_cast<float>(std::ldexp(std::round(std::ldexp(fraction, kStoredSignificantBits)),
                                       exponent - kStoredSignificantBits));
}

void round_to_stored_precision(SubspaceModel& model) {
  for (float& v : model.colour_mean) v = to_stored_precision(v);
  for (float& v : model.colour_transform) v = to_stored_precision(v);
  for (CarBandModel& band : model.bands) {
    band.mean = to_stored_precision(band.mean);
    band.band_std = to_stored_precision(band.band_std);
    band.sigma = to_stored_precision(band.sigma);
  }
}

// The model of prepared channels (the smooth texture the CAR is to reproduce) on a pyramid of `levels`
// levels; notes name the band they concern.
SubspaceModel fit_channels(const std::vector<Plane>& channels, LightView pair, std::uint32_t levels,
                           const AnalysisOptions& options, std::vector<std::string>& notes) {
  const ColourPca pca = fit_colour_pca(channels);
  const std::vector<Plane> bands = to_bands(pca, channels);
  SubspaceModel model;
  model.light = pair.light;
  model.view = pair.view;
  model.width = static_cast<std::uint32_t>(channels[0].cols());
  model.height = static_cast<std::uint32_t>(channels[0].rows());
  model.channels = 3;
  for (int i = 0; i < 3; ++i) {
    model.colour_mean.push_back(static_cast<float>(pca.mean(i)));
    for (int j = 0; j < 3; ++j) model.colour_transform.push_back(static_cast<float>(pca.basis(i, j)));
  }
  std::vector<std::vector<Plane>> pyramids;
  for (const Plane& band : bands) pyramids.push_back(build_laplacian_pyramid(band, static_cast<int>(levels)));
  model.levels = static_cast<std::uint32_t>(pyramids[0].size());
  for (std::uint32_t level = 0; level < model.levels; ++level) {
    for (std::uint32_t channel = 0; channel < 3; ++channel) {
      const CarFit fit = fit_car_band(pyramids[channel][level], options.car);
      model.bands.push_back(fit.model);
      if (!fit.note.empty())
        notes.push_back("level " + std::to_string(level) + " band " + std::to_string(channel) + ": " +
                        fit.note);
    }
  }
  if (options.calibrate_collapse) calibrate_collapse_variance(model, bands, pyramids);
  round_to_stored_precision(model);
  return model;
}

// The groups of bands whose sigma gains the analysis chooses, in this order, each gain on top of the ones
// before. The fitted noise spreads its variance over the pyramid's levels unlike the measurement: the
// finest level's (periods of 2 to 4 texels) is too strong, chroma most, since the CAR's residual there is
// white where a measured image's colour is band-limited (the camera's and the JPEG's 4:2:0 chroma); the
// coarser levels' is too weak, by 5 to 10 dB in coast_sand_rocks' a* at periods of 16 to 64 texels (its
// moss and sand patches). So the finest level's gains come first, then the coarser levels', which may
// also raise them, each on all bands and then on the chroma alone; last the gains on every band and on
// the chroma bands, which scale the whole model (where the tone already gives the threads their
// colours, the CAR's chroma is blotches). With the whole-model gains first, a subspace at grazing light
// took 0 and lost its colour for good, whatever the later groups offered (docs/design.md 5.3).
enum class Scales { every, finest, coarser };
// AnalysisOptions::noise_gains, and noise_raises or chroma_raises
enum class Gains { lower, lower_or_raise };
struct GainGroup {
  const char* name;  // in the analysis log
  bool chroma_only;
  Scales scales;
  Gains gains;
};
constexpr std::array<GainGroup, 6> kGainGroups{
    {{"finest level", false, Scales::finest, Gains::lower},
     {"its chroma", true, Scales::finest, Gains::lower},
     {"coarser levels", false, Scales::coarser, Gains::lower_or_raise},
     {"their chroma", true, Scales::coarser, Gains::lower_or_raise},
     {"every band", false, Scales::every, Gains::lower},
     {"chroma bands", true, Scales::every, Gains::lower}}};

// The draws that score a chosen subspace model apart from its choice (fit_subspace's held-out
// distance): their seeds start kHeldOutSeedOffset after the analysis seed, beyond the candidates' draws
// (AnalysisOptions::selection_draws, at most 16).
constexpr std::uint64_t kHeldOutSeedOffset = 1000;
constexpr std::uint64_t kHeldOutDraws = 2;

// The subspace models' mean texture distance from their measured images: at the draws their candidates
// were chosen on, and at held-out draws.
struct SubspaceScores {
  double chosen = 0.0;
  double held_out = 0.0;
};

// One subspace image stands for every pair of its cluster, and the render shows it at each through that
// pair's light and view: so a candidate is scored at its representative and at kAlsoScoredPairs more
// members, spread evenly over the cluster in (light, view) order. More members were measured no nearer
// (docs/design.md 5.2).
constexpr std::size_t kAlsoScoredPairs = 2;
std::vector<LightView> also_scored_pairs(const BtfDataset& dataset, const Segmentation& segmentation,
                                         std::size_t subspace) {
  const LightView representative = segmentation.representatives[subspace];
  std::vector<LightView> members;
  for (std::uint32_t l = 0; l < segmentation.lights; ++l) {
    for (std::uint32_t v = 0; v < segmentation.views; ++v) {
      const LightView pair{l, v};
      if (segmentation.index[std::size_t{l} * segmentation.views + v] == subspace &&
          dataset.has_image(pair) && !(l == representative.light && v == representative.view))
        members.push_back(pair);
    }
  }
  std::vector<LightView> chosen;
  const std::size_t count = std::min(kAlsoScoredPairs, members.size());
  for (std::size_t i = 0; i < count; ++i)
    chosen.push_back(members[(2 * i + 1) * members.size() / (2 * count)]);
  return chosen;
}

// A measured pair a subspace model is scored at: its image's statistics and what the render pass adds to
// the subspace image there (the light's relit factor and highlights, the view's parallax).
struct ScoredPair {
  DistributionStatistics measured;
  Plane relit;
  Plane highlight;
  ParallaxView view;
  // Per channel, the measured image's linear mean where the model is to be brought to it, as the pair
  // gains will (empty at the representative, whose smooth texture is already matched to it).
  std::vector<double> mean;
};

// The model of one subspace image; notes name the band they concern.
SubspaceModel fit_subspace(const BtfDataset& dataset, LightView pair, std::span<const LightView> also_scored,
                           const Plane& range_map, std::span<const float> horizons,
                           std::span<const Plane> tone, const std::array<float, 3>& chroma,
                           const SpecularLobe& specular, double light_z_floor, const AnalysisOptions& options,
                           std::vector<std::string>& notes, double& chosen_distance,
                           double& held_out_distance) {
  chosen_distance = held_out_distance = 0.0;  // no candidates scored
  const std::uint32_t width = dataset.width(), height = dataset.height();
  std::vector<float> rgb(dataset.pixel_count() * 3);
  dataset.linear_rgb(pair, rgb);
  std::vector<Plane> channels(3, Plane(height, width));
  for (std::size_t p = 0; p < dataset.pixel_count(); ++p) {
    for (int k = 0; k < 3; ++k)
      channels[static_cast<std::size_t>(k)](static_cast<Eigen::Index>(p / width),
                                            static_cast<Eigen::Index>(p % width)) = rgb[p * 3 + k];
  }
  const bool toned = !tone.empty();
  if (toned || options.deshade_floor > 0.0) {
    undo_parallax(channels, range_map, dataset.views()[pair.view].vector(), kAnalysisParallaxScale);
  }
  // The highlights the render pass adds on its own are no part of the smooth texture.
  const Plane highlight = lobe_of(specular, range_map, dataset.lights()[pair.light].vector(),
                                  dataset.views()[pair.view].vector(), horizons);
  if (specular.strength > 0.0) {
    for (Plane& channel : channels) channel -= highlight;
  }
  const Plane relit = relit_factor(range_map, dataset.lights()[pair.light].vector(), light_z_floor, horizons);
  // The smooth texture a model of tone weight `weight` is fitted to: the tone's share and, with
  // --deshade, the relit factor divided out.
  const auto prepared = [&](double weight) {
    std::vector<Plane> smooth = channels;
    if (toned && weight > 0.0) divide_shading(smooth, weighted_tone(tone, weight, chroma), kReliefToneFloor);
    if (options.deshade_floor > 0.0) divide_shading(smooth, relit, options.deshade_floor);
    return smooth;
  };
  if (!toned || options.remainder_clamps.empty()) {
    std::vector<Plane> smooth = prepared(1.0);
    const std::vector<Plane> untoned{Plane::Ones(height, width)};
    match_render_mean(smooth, channels, weighted_tone(toned ? tone : untoned, 1.0, chroma), relit);
    return fit_channels(smooth, pair, options.pyramid_levels, options, notes);
  }

  // Each candidate (tone weight, clamp) gives a model; the one whose image, as the render pass
  // composes it (smooth texture x its share of the tone x relit factor), is nearest the measured image
  // by the texture measure (texture_distributions.hpp) wins.
  const DistributionStatistics measured = distribution_statistics(rgb, width, height);
  const std::vector<double> weights =
      options.tone_weights.empty() ? std::vector<double>{1.0} : options.tone_weights;
  std::vector<std::uint32_t> level_counts{options.pyramid_levels};
  for (const std::uint32_t levels : options.other_level_counts) {
    if (std::find(level_counts.begin(), level_counts.end(), levels) == level_counts.end())
      level_counts.push_back(levels);
  }
  std::optional<SubspaceModel> best;
  double best_score = 0.0, best_distance = 0.0, best_clamp = 0.0;
  std::vector<Plane> best_share;
  std::vector<std::string> best_notes;
  const std::size_t candidates = weights.size() * options.remainder_clamps.size() * level_counts.size();
  const std::uint32_t draws =
      candidates > 1 ? options.selection_draws : 1;  // one candidate needs no choosing
  // The pairs each candidate is scored at: the representative first.
  std::vector<ScoredPair> scored;
  scored.push_back(
      {measured, relit, highlight, ParallaxView(range_map, dataset.views()[pair.view].vector()), {}});
  for (const LightView member : also_scored) {
    std::vector<float> member_rgb(rgb.size());
    dataset.linear_rgb(member, member_rgb);
    std::vector<double> mean(3, 0.0);
    for (std::size_t p = 0; p < member_rgb.size(); ++p)
      mean[p % 3] += member_rgb[p] / static_cast<double>(dataset.pixel_count());
    const std::array<double, 3> light = dataset.lights()[member.light].vector(),
                                view = dataset.views()[member.view].vector();
    scored.push_back({distribution_statistics(member_rgb, width, height),
                      relit_factor(range_map, light, light_z_floor, horizons),
                      lobe_of(specular, range_map, light, view, horizons), ParallaxView(range_map, view),
                      std::move(mean)});
  }
  // The mean distance over `draws` draws and the scored pairs of a candidate's model image as the render
  // pass shows it: smooth texture x its share of the tone x the pair's relit factor, plus its highlights,
  // through its view's parallax. Draw d of every candidate uses the same noise, so only the model differs
  // between candidates.
  const auto distance_of = [&](const SubspaceModel& model, const std::vector<Plane>& share,
                               std::uint64_t first_seed) {
    Material single;
    single.subspaces.push_back(model);
    double distance = 0.0;
    std::vector<float> texture(rgb.size()), image(rgb.size());
    for (std::uint32_t draw = 0; draw < draws; ++draw) {
      reference::SubspaceBlock block;  // the default burn-in, as synthesis uses
      block.seed = first_seed + draw;
      block.width = width;
      block.height = height;
      reference::synthesize_subspace(single, 0, block, texture);
      for (const ScoredPair& at : scored) {
        image = texture;
        apply_relief(image, share, at.relit);
        if (specular.strength > 0.0) {
          for (std::size_t p = 0; p < image.size(); ++p)
            image[p] += static_cast<float>(at.highlight.data()[p / 3]);  // a row-major plane
        }
        std::vector<float> shown = at.view.shown(image, 3);
        if (!at.mean.empty()) {
          std::array<double, 3> sum{};
          for (std::size_t p = 0; p < shown.size(); ++p) sum[p % 3] += shown[p];
          for (std::size_t p = 0; p < shown.size(); ++p) {
            const double model_mean = sum[p % 3] / static_cast<double>(dataset.pixel_count());
            if (model_mean > 0.0) shown[p] = static_cast<float>(shown[p] * at.mean[p % 3] / model_mean);
          }
        }
        distance += distribution_distance(distribution_statistics(shown, width, height), at.measured).total /
                    (draws * static_cast<double>(scored.size()));
      }
    }
    return distance;
  };
  for (const double weight : weights) {
    const std::vector<Plane> smooth = prepared(weight);
    const std::vector<Plane> share = weighted_tone(tone, weight, chroma);
    for (const double clamp : options.remainder_clamps) {
      std::vector<Plane> clamped = smooth;
      if (clamp > 0.0) clamp_remainder(clamped, clamp);
      match_render_mean(clamped, channels, share, relit);
      for (const std::uint32_t levels : level_counts) {
        std::vector<std::string> candidate_notes;
        SubspaceModel candidate = fit_channels(clamped, pair, levels, options, candidate_notes);
        candidate.tone_weight = static_cast<float>(weight);
        // One draw's distance varies by about as much as the candidates differ (on fabric the choice
        // followed the noise stream), so a candidate scores the mean over several draws.
        const double distance = distance_of(candidate, share, options.segmentation.seed);
        // Another level count has to be clearly nearer: within one draw's noise the default stays.
        const double score =
            levels == options.pyramid_levels ? distance : distance * (1.0 + kLevelChoiceMargin);
        if (!best || score < best_score) {
          best = std::move(candidate);
          best_score = score;
          best_distance = distance;
          best_clamp = clamp;
          best_share = share;
          best_notes = std::move(candidate_notes);
        }
      }
    }
  }
  // The gains on the bands' sigma, group after group, each on top of the ones chosen before it.
  std::array<double, kGainGroups.size()> chosen_gains;
  chosen_gains.fill(1.0);
  std::size_t gain_candidates = 0;
  for (std::size_t group = 0; group < kGainGroups.size(); ++group) {
    const GainGroup& g = kGainGroups[group];
    if (!options.gains_per_scale && g.scales != Scales::every) continue;
    const SubspaceModel chosen = *best;
    const auto selected = [&](std::size_t band) {
      const std::size_t level = band / chosen.channels, channel = band % chosen.channels;
      return (!g.chroma_only || channel != 0) &&
             (g.scales == Scales::every || (level == 0) == (g.scales == Scales::finest));
    };
    bool any = false;
    for (std::size_t b = 0; b < chosen.bands.size(); ++b) any = any || selected(b);
    if (!any) continue;  // a one-level model has no coarser levels
    std::vector<double> gains = options.noise_gains;
    if (g.gains == Gains::lower_or_raise) {
      const std::vector<double>& raises = g.chroma_only ? options.chroma_raises : options.noise_raises;
      gains.insert(gains.end(), raises.begin(), raises.end());
    }
    for (const double gain : gains) {
      if (gain == 1.0) continue;
      ++gain_candidates;
      SubspaceModel candidate = chosen;
      for (std::size_t b = 0; b < candidate.bands.size(); ++b) {
        if (selected(b))
          candidate.bands[b].sigma = to_stored_precision(static_cast<float>(candidate.bands[b].sigma * gain));
      }
      const double distance = distance_of(candidate, best_share, options.segmentation.seed);
      if (distance < best_distance) {
        best = std::move(candidate);
        best_distance = distance;
        chosen_gains[group] = gain;
      }
    }
  }
  notes = std::move(best_notes);
  char part[160];
  std::snprintf(part, sizeof part, "tone weight %.2g, remainder clamp %.2g, %u pyramid levels, noise gains:",
                static_cast<double>(best->tone_weight), best_clamp, best->levels);
  std::string line = part;
  for (std::size_t group = 0; group < kGainGroups.size(); ++group) {
    std::snprintf(part, sizeof part, "%s %s %.2g", group == 0 ? "" : ",", kGainGroups[group].name,
                  chosen_gains[group]);
    line += part;
  }
  std::snprintf(part, sizeof part, " chosen of %zu candidates (texture distance %.3f, mean of %u draws",
                candidates + gain_candidates, best_distance, draws);
  line += part;
  for (std::size_t m = 0; m < also_scored.size(); ++m) {
    std::snprintf(part, sizeof part, "%s(light %u, view %u)", m == 0 ? " and of the pairs " : ", ",
                  also_scored[m].light, also_scored[m].view);
    line += part;
  }
  notes.push_back(line + ")");
  chosen_distance = best_distance;
  // The chosen model's distance at draws no candidate was chosen on: the minimum over the candidates is
  // biased low by the draw's own noise, this is not, so two analyses compare fairly by it.
  for (std::uint64_t d = 0; d < kHeldOutDraws; ++d) {
    held_out_distance +=
        distance_of(*best, best_share, options.segmentation.seed + kHeldOutSeedOffset + d) / kHeldOutDraws;
  }
  return *best;
}

// The specular lobe as the material stores it, as the render pass will draw it.
SpecularLobe stored_lobe(const Material& material) {
  return {material.range.specular_strength, material.range.specular_gloss,
          material.range.specular_view_power};
}

}  // namespace

AnalysisResult analyze_btf(const BtfDataset& dataset, const AnalysisOptions& options,
                           const std::function<void(const std::string&)>& log) {
  if (options.pyramid_levels < 1 || options.pyramid_levels > 6)
    throw std::invalid_argument("pyramid levels must be within 1..6");
  for (const std::uint32_t levels : options.other_level_counts) {
    if (levels < 1 || levels > 6)
      throw std::invalid_argument("other pyramid level counts must be within 1..6");
  }
  if (options.selection_draws < 1 || options.selection_draws > 16)
    throw std::invalid_argument("selection draws must be within 1..16");
  if (options.tiling_candidates < 1 || options.tiling_candidates > 64)
    throw std::invalid_argument("range tiling candidates must be within 1..64");
  if (dataset.present_pairs().empty()) throw std::invalid_argument("the dataset holds no images");
  AnalysisResult result;
  auto note = [&](const std::string& line) {
    result.log.push_back(line);
    if (log) log(line);
  };

  {
    StageClock clock(result, "segmentation");
    SegmentationOptions segmentation = options.segmentation;
    segmentation.threads = options.threads;
    segmentation.progress = options.progress;
    result.segmentation = segment_btf(dataset, segmentation);
  }
  note("segmentation: " + std::to_string(result.segmentation.representatives.size()) + " subspaces after " +
       std::to_string(result.segmentation.iterations) + " k-means iterations");

  std::optional<NormalMap> strict_normals;  // AnalysisOptions::strict_stereo's candidate
  {
    StageClock clock(result, "photometric stereo");
    result.stereo_view =
        options.stereo_view >= 0 ? static_cast<std::uint32_t>(options.stereo_view) : top_view(dataset);
    if (result.stereo_view >= dataset.views().size())
      throw std::invalid_argument("the stereo view index is out of range");
    PhotometricStereoOptions stereo = options.stereo;
    stereo.threads = options.threads;
    if (options.strict_stereo == AutoChoice::always)
      stereo.dark_fraction = std::max(stereo.dark_fraction, kStrictStereoDarkFraction);
    result.normals = photometric_stereo(dataset, result.stereo_view, stereo);
    const bool strict_candidate = options.relief_tone && options.relief_shadows == AutoChoice::automatic &&
                                  options.strict_stereo == AutoChoice::automatic &&
                                  stereo.dark_fraction < kStrictStereoDarkFraction;
    if (strict_candidate) {
      stereo.dark_fraction = kStrictStereoDarkFraction;
      strict_normals = photometric_stereo(dataset, result.stereo_view, stereo);
    }
  }
  char line[200];
  std::snprintf(line, sizeof line, "photometric stereo: view %u, normals for %.1f%% of pixels",
                result.stereo_view, valid_percent(result.normals));
  note(line);

  for (const Direction& d : dataset.lights()) result.material.lights.push_back(to_material(d));
  for (const Direction& d : dataset.views()) result.material.views.push_back(to_material(d));
  const double z_floor = relight_floor(result.material);  // the render pass's, from the light set
  // The range map's Wang tiles with `tone`: the first time, the best-looking of the candidate tilings
  // (range/range_tiling_choice.hpp); after, the same tiling again, since only the tone changes.
  std::optional<std::uint64_t> tiling_seed;
  std::size_t tiling_draw = 0;  // the kept draw's index
  const auto tile_relief = [&](std::span<const Plane> tone, double shadow_scale) {
    RangeTileOptions tiles = options.tiles;
    tiles.seed = options.segmentation.seed;
    if (tiling_seed) {
      tiles.seed = *tiling_seed;
      return build_range_tiles(result.range_map, tiles, tone);
    }
    RangeTilingChoice choice = choose_range_tiling(result.range_map, tiles, tone, {z_floor, shadow_scale},
                                                   options.tiling_candidates, options.threads);
    tiling_seed = choice.seed;
    tiling_draw = choice.chosen;
    if (choice.distances.size() > 1) {
      const auto [lowest, highest] = std::minmax_element(choice.distances.begin(), choice.distances.end());
      std::snprintf(line, sizeof line,
                    "range tiling: draw %zu of %zu kept (its relief's texture distance from the whole map's "
                    "%.3f; the draws' %.3f to %.3f)",
                    choice.chosen + 1, choice.distances.size(), choice.distances[choice.chosen], *lowest,
                    *highest);
      note(line);
    }
    return std::move(choice.tiles);
  };
  // The tone, its planes and the range tiles, for the highlights `lobe` (none: strength 0), the tone
  // band-limited where `band_limited`.
  const auto relief_stage = [&](const SpecularLobe& lobe, double shadow_scale, bool band_limited = false) {
    result.tone = relief_tone(dataset, result.stereo_view, result.range_map, z_floor, result.horizons, lobe);
    result.tone_planes = {result.tone};
    if (options.tone_planes != TonePlanes::never) {
      std::vector<Plane> planes =
          relief_tone_planes(dataset, result.stereo_view, result.range_map, z_floor, result.horizons, lobe);
      const double deviation = tone_colour_deviation(planes);
      const bool coloured = options.tone_planes == TonePlanes::always || deviation >= kToneColourVisible;
      if (coloured) result.tone_planes = std::move(planes);
      std::snprintf(line, sizeof line, "relief tone: colour deviation %.3f, %s", deviation,
                    coloured ? "stored as R, G and B planes" : "stored grey");
      note(line);
    }
    if (band_limited) {
      result.tone = band_limited_tone(result.tone);
      if (result.tone_planes.size() == 1) {
        result.tone_planes.front() = result.tone;  // a grey tone is the one plane: filtered once
      } else {
        for (Plane& plane : result.tone_planes) plane = band_limited_tone(plane);
      }
    }
    result.material.range = tile_relief(result.tone_planes, shadow_scale);
    result.material.range.shadow_scale = static_cast<float>(shadow_scale);
    result.material.range.specular_strength = static_cast<float>(lobe.strength);
    result.material.range.specular_gloss = static_cast<float>(lobe.gloss);
    result.material.range.specular_view_power =
        lobe.strength > 0.0 ? static_cast<float>(lobe.view_power) : 0.0f;
    result.material.range.chroma_levels = relief_chroma_levels(dataset.chroma_halvings);
    if (options.coloured_tone && result.tone_planes.size() == 1) {
      result.material.range.tone_chroma =
          relief_tone_chroma(dataset, result.stereo_view, result.range_map, z_floor, result.tone,
                             result.horizons, stored_lobe(result.material));
    }
  };
  // The subspace models over the relief in result.material.range; their mean texture distance at the
  // draws they were chosen on, and at held-out draws.
  std::vector<std::vector<std::string>> subspace_notes;
  const auto subspace_stage = [&] {
    const auto& representatives = result.segmentation.representatives;
    subspace_notes.assign(representatives.size(), {});
    std::vector<double> distances(representatives.size(), 0.0), held_out(representatives.size(), 0.0);
    result.material.subspaces.resize(representatives.size());
    Progress progress("subspace models", representatives.size(), options.progress);
    // The analysis goes on with the lobe as stored, as the render pass will draw it.
    const SpecularLobe lobe = stored_lobe(result.material);
    detail::parallel_for(representatives.size(), options.threads, [&](std::size_t s) {
      result.material.subspaces[s] = fit_subspace(
          dataset, representatives[s], also_scored_pairs(dataset, result.segmentation, s), result.range_map,
          result.horizons, result.tone_planes, result.material.range.tone_chroma, lobe, z_floor, options,
          subspace_notes[s], distances[s], held_out[s]);
      progress.advance();
    });
    SubspaceScores scores;
    for (std::size_t s = 0; s < distances.size(); ++s) {
      scores.chosen += distances[s] / static_cast<double>(distances.size());
      scores.held_out += held_out[s] / static_cast<double>(distances.size());
    }
    return scores;
  };

  SpecularLobe specular;  // the relief's highlights, fitted with the tone
  double shadow_scale = 0.0;
  // Whether the stored tone is band-limited (AnalysisOptions::tone_band_limit).
  bool tone_band_limited = options.relief_tone && options.tone_band_limit == AutoChoice::always;
  {
    StageClock clock(result, "range map and tiles");
    result.range_map = relief_of(result.normals);
    if (options.relief_tone) {
      if (options.relief_shadows == AutoChoice::always) shadow_scale = 1.0;
      if (options.relief_shadows == AutoChoice::automatic) {
        ShadowFit fit = fit_shadow_scale(dataset, result.stereo_view, result.range_map, z_floor);
        if (strict_normals) {
          Plane strict_map = relief_of(*strict_normals);
          const ShadowFit strict_fit = fit_shadow_scale(dataset, result.stereo_view, strict_map, z_floor);
          const bool keep = strict_fit.error <= (1.0 - kShadowFitGain) * fit.error;
          std::snprintf(line, sizeof line,
                        "photometric stereo: samples under %.2f of the brightest rejected: %s (normals for "
                        "%.1f%% of pixels; images explained with error %.4f, %.4f without)",
                        kStrictStereoDarkFraction, keep ? "kept" : "not kept", valid_percent(*strict_normals),
                        strict_fit.error, fit.error);
          note(line);
          if (keep) {
            result.normals = std::move(*strict_normals);
            result.range_map = std::move(strict_map);
            fit = strict_fit;
          }
        }
        shadow_scale = fit.scale;
        std::snprintf(line, sizeof line,
                      "relief shadows: scale %.2f%s (the view's images explained with error %.4f, without "
                      "shadows %.4f)",
                      fit.scale, fit.scale > 0.0 ? "" : ", none", fit.error, fit.error_without);
        note(line);
      }
      result.horizons = range_map_horizons(result.range_map, shadow_scale);
      if (options.relief_specular != AutoChoice::never) {
        const std::vector<SpecularFit> rounds = fit_relief_specular_with_tone(
            dataset, result.stereo_view, result.range_map, z_floor, result.horizons);
        for (std::size_t round = 0; round + 1 < rounds.size(); ++round) {
          std::snprintf(line, sizeof line,
                        "relief specular: strength %.4g, gloss %.0f (error %.4f); fitted again against the "
                        "tone of the images without that lobe",
                        rounds[round].lobe.strength, rounds[round].lobe.gloss, rounds[round].error);
          note(line);
        }
        const SpecularFit& fit = rounds.back();
        specular = fit.lobe;
        std::snprintf(line, sizeof line,
                      "relief specular: strength %.4g, gloss %.0f%s (the view's images explained with error "
                      "%.4f, without it %.4f)",
                      fit.lobe.strength, fit.lobe.gloss, fit.lobe.strength > 0.0 ? "" : ", none", fit.error,
                      fit.error_without);
        note(line);
      }
      // The tone of the images without their highlights, which the render adds apart from it.
      relief_stage(specular, shadow_scale, tone_band_limited);
    } else {
      result.material.range = tile_relief({}, 0.0);
    }
  }

  // What a choice between two reliefs sets aside while it fits the other: the material, its tone and
  // the subspace models' notes.
  struct ReliefModels {
    Material material;
    Plane tone;
    std::vector<Plane> tone_planes;
    std::vector<std::vector<std::string>> notes;
  };
  const auto keep_models = [&] {
    return ReliefModels{result.material, result.tone, result.tone_planes, subspace_notes};
  };
  const auto restore_models = [&](ReliefModels&& kept) {
    result.material = std::move(kept.material);
    result.tone = std::move(kept.tone);
    result.tone_planes = std::move(kept.tone_planes);
    subspace_notes = std::move(kept.notes);
  };
  {
    StageClock clock(result, "subspace models");
    SubspaceScores first = subspace_stage();
    // A fitted lobe grows with the view's tilt (SpecularLobe::view_power, kSpecularViewPower) where the
    // subspace models, scored at their pairs' views, look nearer with it by kSpecularKeepMargin; else it is
    // the same at every view, as fitted.
    // Leather's look nearer (0.4447 against 0.4588 at 256^2), fabric's and coast_sand_rocks' do not (0.4676
    // against 0.4621, 0.3582 against 0.3439), and coast_sand_rocks' would then leave the lobe out
    // (docs/design.md 5.2).
    if (specular.strength > 0.0) {
      ReliefModels same = keep_models();
      // The fitted lobe, which is the stereo view's, with the same highlights at that view.
      SpecularLobe growing = specular;
      growing.view_power = kSpecularViewPower;
      growing.strength /=
          specular_view_gain(static_cast<float>(growing.view_power),
                             static_cast<float>(dataset.views()[result.stereo_view].vector()[2]));
      relief_stage(growing, shadow_scale, tone_band_limited);
      const SubspaceScores growing_scores = subspace_stage();
      const bool grows = growing_scores.chosen < first.chosen * (1.0 - kSpecularKeepMargin);
      std::snprintf(line, sizeof line,
                    "relief specular: %s (the subspace models' mean texture distance %.4f growing, %.4f the "
                    "same at every view)",
                    grows ? "grows with the view's tilt" : "the same at every view", growing_scores.chosen,
                    first.chosen);
      note(line);
      if (grows) {
        specular = growing;
        first = growing_scores;
      } else {
        restore_models(std::move(same));
      }
    }
    const double with_lobe = first.chosen;
    SubspaceScores kept_scores = first;  // the kept models'
    // Automatic: a fitted lobe stays where the subspace models look nearer the measurement with it by
    // kSpecularKeepMargin. It explains the stereo view's images better on every sample, but
    // coast_sand_rocks' renders look further with it (docs/design.md 5.2 and 5.3). The distances at the
    // chosen draws, not the held-out ones the tone's choice compares: at held-out draws coast_sand_rocks
    // keeps the lobe (0.4191 against 0.4261 at 256^2), and its fidelity goes 0.157 / 0.303 -> 0.182 /
    // 0.359 (five / spread16, seeds 1-3).
    if (options.relief_specular == AutoChoice::automatic && specular.strength > 0.0) {
      ReliefModels with = keep_models();
      relief_stage({}, shadow_scale, tone_band_limited);
      const SubspaceScores without = subspace_stage();
      const double without_lobe = without.chosen;
      const bool keep = with_lobe < without_lobe * (1.0 - kSpecularKeepMargin);
      if (!keep) kept_scores = without;
      std::snprintf(
          line, sizeof line,
          "relief specular: %s (the subspace models' mean texture distance %.4f with it, %.4f without)",
          keep ? "kept" : "left out", with_lobe, without_lobe);
      note(line);
      if (keep) restore_models(std::move(with));
    }
    // Automatic: the band-limited tone where the subspace models, refitted over it with the tiling and
    // the lobe kept so far, look nearer by kToneBandLimitMargin.
    if (options.relief_tone && options.tone_band_limit == AutoChoice::automatic) {
      ReliefModels sharp = keep_models();
      relief_stage(stored_lobe(result.material), shadow_scale, true);
      const SubspaceScores band_limited = subspace_stage();
      const bool keep = band_limited.held_out < kept_scores.held_out * (1.0 - kToneBandLimitMargin);
      std::snprintf(line, sizeof line,
                    "relief tone: %s (the subspace models' mean texture distance at held-out draws %.4f "
                    "band-limited, %.4f as measured; at their own draws %.4f, %.4f)",
                    keep ? "band-limited" : "kept as measured", band_limited.held_out, kept_scores.held_out,
                    band_limited.chosen, kept_scores.chosen);
      note(line);
      tone_band_limited = keep;
      if (!keep) restore_models(std::move(sharp));
    }
    const auto& representatives = result.segmentation.representatives;
    for (std::size_t s = 0; s < subspace_notes.size(); ++s) {
      for (const std::string& n : subspace_notes[s]) {
        note("subspace " + std::to_string(s) + " (light " + std::to_string(representatives[s].light) +
             ", view " + std::to_string(representatives[s].view) + ") " + n);
      }
    }
  }
  specular = stored_lobe(result.material);
  if (result.material.range.tile_size > 0) {
    std::snprintf(line, sizeof line,
                  "relief chroma: read %u mip level(s) above its brightness (the images' colour resolution "
                  "halved %u time(s) below their brightness's)",
                  result.material.range.chroma_levels, dataset.chroma_halvings);
    note(line);
  }

  result.material.subspace_index = result.segmentation.index;
  if (options.pair_gains) {
    StageClock clock(result, "pair gains");
    Progress progress("pair gains", dataset.lights().size(), options.progress);
    result.material.pair_gains = fit_pair_gains(
        dataset, result.material, {result.range_map, result.tone_planes, result.horizons, specular},
        options.segmentation.seed, options.threads, [&] { progress.advance(); });
  }
  Material& material = result.material;
  material.settings = {
      {"source", dataset.source},
      {"image_size", std::to_string(dataset.width()) + "x" + std::to_string(dataset.height())},
      {"subspaces", std::to_string(options.segmentation.clusters)},
      {"histogram_bins", std::to_string(options.segmentation.bins)},
      {"seed", std::to_string(options.segmentation.seed)},
      {"pyramid_levels", std::to_string(options.pyramid_levels)},
      {"car_prior_delta", std::to_string(options.car.prior_delta)},
      {"car_prior_beta0", std::to_string(options.car.prior_beta0)},
      {"car_stability_margin", std::to_string(options.car.stability_margin)},
      {"calibrate_collapse", options.calibrate_collapse ? "yes" : "no"},
      {"relief_tone", options.relief_tone ? "yes" : "no"},
      {"coloured_tone", options.relief_tone && options.coloured_tone ? "where it explains the colour" : "no"},
      {"tone_planes", describe_choice(options.tone_planes, "where its colour is visible")},
      {"relief_shadows", describe_choice(options.relief_shadows, "where they explain the images")},
      {"strict_stereo", describe_choice(options.strict_stereo, "where it explains the images")},
      {"remainder_clamps", join_numbers(options.remainder_clamps)},
      {"selection_draws", std::to_string(options.selection_draws)},
      {"deshade_floor", std::to_string(options.deshade_floor)},
      {"pair_gains", options.pair_gains ? "yes" : "no"},
      {"relief_specular",
       describe_choice(options.relief_specular, "where the models look nearer with it", "fitted")},
      {"tone_band_limit", options.relief_tone && options.tone_band_limit == AutoChoice::automatic
                              ? (tone_band_limited ? "yes: the models look nearer with it"
                                                   : "no: the models look no nearer with it")
                              : (tone_band_limited ? "yes" : "no")},
      {"stereo_view", std::to_string(result.stereo_view)},
      {"tile_size", std::to_string(material.range.tile_size)},
      {"tilings", options.tiling_candidates == 1
                      ? "one draw"
                      : "draw " + std::to_string(tiling_draw + 1) + ", the best-looking of " +
                            std::to_string(options.tiling_candidates)},
      {"edge_colours", std::to_string(material.range.edge_colours)},
  };
  return result;
}

}  // namespace carbtf
