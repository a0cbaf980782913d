// The CAR noise tested where it is visible (issue 42 item 2): the synthesized subspace images, each
// composed with its relief as the render pass does (subspace_fidelity()), against the measured images
// they were fitted to. The analysis chooses each subspace's noise gain by the texture measure, so a
// fitted model's noise must be the measure's best: every sigma halved or doubled, or the largest CAR
// coefficient of every band sign-flipped, must look further from the measurement. Tested on the two
// samples whose fitted models keep their noise (coast_sand_rocks' moss, fabric's fibres); leather's
// cells are flat, and its fitted gains (0 to 0.35) leave a CAR whose coefficients the render hardly shows.
// And the gains per scale must beat one gain for every level on a draw the analysis did not choose on.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/quality/subspace_fidelity.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material/car_stability.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "test_top_view.hpp"

namespace carbtf {
namespace {

constexpr std::uint32_t kSize = 64;

// The mean rel over the synthesis seeds 7 to 11, none the analysis' own, so that the choice must hold for
// other draws too. A mean over draws, the same draws for every model compared: one draw's rel differs
// from the next by about 1% (fabric at 64^2: 0.303 to 0.312), as much as a coefficient's flipped sign
// moves it, so a single draw ranks the draw as much as the model.
double mean_rel(const Material& material, const std::vector<RgbField>& measured) {
  constexpr std::uint64_t kFirstSeed = 7, kDraws = 5;
  double sum = 0.0;
  for (std::uint64_t seed = kFirstSeed; seed < kFirstSeed + kDraws; ++seed) {
    reference::SubspaceBlock block;
    block.seed = seed;
    block.width = kSize;
    block.height = kSize;
    SynthesizedImages images;
    images.width = images.height = kSize;
    images.images = reference::synthesize_subspaces(material, {}, block);
    for (const SubspaceModel& s : material.subspaces) images.channels.push_back(s.channels);
    const SubspaceFidelity f = subspace_fidelity(material, images, measured);
    REQUIRE(f.pairs == material.subspaces.size());
    sum += f.mean_rel;
  }
  return sum / static_cast<double>(kDraws);
}

Material with_sigma_times(Material m, float factor) {
  for (SubspaceModel& s : m.subspaces)
    for (CarBandModel& band : s.bands) band.sigma *= factor;
  return m;
}

// The largest coefficient of every band sign-flipped, where the recursion stays stable.
Material sign_flipped(Material m, int& flips) {
  for (SubspaceModel& s : m.subspaces) {
    for (CarBandModel& band : s.bands) {
      if (band.gamma.empty() || band.sigma == 0.0f) continue;
      std::size_t largest = 0;
      for (std::size_t k = 1; k < band.gamma.size(); ++k)
        if (std::abs(band.gamma[k]) > std::abs(band.gamma[largest])) largest = k;
      std::vector<double> gamma(band.gamma.begin(), band.gamma.end());
      gamma[largest] = -gamma[largest];
      if (!car_roots_within(band.neighbourhood, gamma, 1.0 - kCarStabilityMargin)) continue;
      band.gamma[largest] = -band.gamma[largest];
      ++flips;
    }
  }
  return m;
}

// The analysis options the cases fit a sample of kSize with (few subspaces and small tiles, for the size).
AnalysisOptions small_sample_options() {
  return test::small_analysis_options(6, 32);
}

}  // namespace

TEST_CASE(
    "a fitted model's noise is the measure's best where it is visible: sigma halved or doubled and a "
    "CAR coefficient's sign flipped look further from the measurement",
    "[analysis][quality][noise][slow]") {
  const std::string name = GENERATE(std::string("coast_sand_rocks"), std::string("fabric"));
  const BtfDataset dataset = test::rendered_sample(name, kSize, 4);
  AnalysisOptions options = small_sample_options();
  const Material fitted = analyze_btf(dataset, options).material;
  const std::vector<RgbField> measured = representative_images(dataset, fitted);
  int flips = 0;
  const Material flipped = sign_flipped(fitted, flips);
  REQUIRE(flips > 0);
  const double fitted_rel = mean_rel(fitted, measured);
  const double halved = mean_rel(with_sigma_times(fitted, 0.5f), measured);
  const double doubled = mean_rel(with_sigma_times(fitted, 2.0f), measured);
  const double flipped_rel = mean_rel(flipped, measured);
  INFO(name << ": fitted rel " << fitted_rel << ", sigma halved " << halved << ", doubled " << doubled
            << ", sign flipped (" << flips << " bands) " << flipped_rel);
  CHECK(halved > fitted_rel);
  CHECK(doubled > fitted_rel);
  CHECK(flipped_rel > fitted_rel);
}

// The gains per scale (analyze.cpp, kGainGroups) are chosen on the analysis' own draw; on another draw
// the model must still look nearer its measurement than the one chosen with a gain for every level alike.
TEST_CASE("noise gains per scale look nearer the measurement than one gain for every level",
          "[analysis][quality][noise][slow]") {
  const std::string name = GENERATE(std::string("coast_sand_rocks"), std::string("fabric"));
  const BtfDataset dataset = test::rendered_sample(name, kSize, 4);
  AnalysisOptions options = small_sample_options();
  // Each sample's tone as its default model at 256^2 has it: band-limited on coast_sand_rocks, as
  // measured on fabric (AnalysisOptions::tone_band_limit). At this size the analysis band-limits
  // fabric's tone too, and over that tone the gains per scale lose to one gain for every level by 0.7%
  // (rel 0.2325 against 0.2310): a fabric whose threads the tone draws sharp is what they are tested on.
  options.tone_band_limit = name == "fabric" ? AutoChoice::never : AutoChoice::always;
  const Material per_scale = analyze_btf(dataset, options).material;
  options.gains_per_scale = false;
  const Material uniform = analyze_btf(dataset, options).material;
  const std::vector<RgbField> measured = representative_images(dataset, per_scale);
  const double per_scale_rel = mean_rel(per_scale, measured);
  const double uniform_rel = mean_rel(uniform, measured);
  INFO(name << ": gains per scale rel " << per_scale_rel << ", one gain for every level " << uniform_rel);
  CHECK(per_scale_rel < uniform_rel);
}

}  // namespace carbtf
