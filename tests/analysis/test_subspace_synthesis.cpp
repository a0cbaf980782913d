// The CPU reference of subspace-image synthesis: collapse and colour transform, determinism, float32
// against float64, fidelity to the analysed image's colour statistics, and interpolation.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "carbtf/reference/synthetic_material.hpp"
#include "test_support.hpp"
#include "test_top_view.hpp"

namespace carbtf {
namespace {

// A sample material rendered as a UBO2003 BTF of size x size images, held in memory.
BtfDataset rendered_sample(const std::string& name, std::uint32_t size) {
  return test::rendered_sample(name, size, 4);
}

// The analysis of a small sample: 4 subspaces, 16-texel range tiles, quiet.
AnalysisOptions small_analysis() {
  return test::small_analysis_options(4, 16);
}

// A one-subspace material over a 2x2 direction set, 3 levels, bands given per level.
Material tiny_material(const std::vector<CarBandModel>& per_level) {
  Material m;
  m.lights = {{0.0f, 0.0f}, {0.5f, 0.0f}, {0.5f, 2.0f}};
  m.views = m.lights;
  m.subspace_index.assign(9, 0);
  SubspaceModel s;
  s.width = s.height = 64;
  s.levels = static_cast<std::uint32_t>(per_level.size());
  s.colour_mean = {0.2f, 0.3f, 0.4f};
  s.colour_transform = {0.6f, 0.0f, 0.8f, 0.0f, 1.0f, 0.0f, -0.8f, 0.0f, 0.6f};
  for (const CarBandModel& band : per_level)
    for (int c = 0; c < 3; ++c) s.bands.push_back(band);
  m.subspaces.push_back(s);
  return m;
}

CarBandModel band(float mean, float sigma, std::vector<float> gamma = {}) {
  CarBandModel b;
  b.mean = mean;
  b.sigma = sigma;
  b.band_std = sigma;
  if (!gamma.empty()) {
    b.neighbourhood = {{0, -1}, {-1, 0}};
    b.gamma = std::move(gamma);
  }
  return b;
}

AnalysisResult analysed_leather() {
  return analyze_btf(rendered_sample("leather", 32), small_analysis());
}

}  // namespace

TEST_CASE("constant bands collapse to the sum of their means through the colour transform", "[synthesis]") {
  const Material m = tiny_material({band(0.5f, 0.0f), band(0.25f, 0.0f), band(-0.125f, 0.0f)});
  REQUIRE(validate_material(m).ok());
  reference::SubspaceBlock block;
  block.width = 37;
  block.height = 21;
  block.row0 = -5;
  block.col0 = 1000;
  std::vector<double> out(37 * 21 * 3);
  reference::synthesize_subspace(m, 0, block, std::span<double>(out));
  const double sum = 0.5 + 0.25 - 0.125;
  const double expected[3] = {0.2 + (0.6 + 0.8) * sum, 0.3 + sum, 0.4 + (-0.8 + 0.6) * sum};
  for (std::size_t p = 0; p < 37 * 21; ++p)
    for (int c = 0; c < 3; ++c) REQUIRE(out[p * 3 + c] == Approx(expected[c]).margin(1e-7));
}

TEST_CASE("subspace synthesis is deterministic, and float32 follows float64", "[synthesis]") {
  const Material m = tiny_material(
      {band(0.0f, 0.05f, {0.5f, 0.4f}), band(0.0f, 0.1f, {0.45f, 0.45f}), band(0.1f, 0.2f, {0.6f, 0.35f})});
  reference::SubspaceBlock block;
  block.seed = 77;
  block.width = block.height = 256;
  std::vector<float> a(256 * 256 * 3), b(a.size());
  std::vector<double> wide(a.size());
  reference::synthesize_subspace(m, 0, block, std::span<float>(a));
  reference::synthesize_subspace(m, 0, block, std::span<float>(b));
  REQUIRE(a == b);
  reference::synthesize_subspace(m, 0, block, std::span<double>(wide));
  double mean = 0.0, square = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    mean += wide[i];
    square += wide[i] * wide[i];
    worst = std::max(worst, std::abs(a[i] - wide[i]));
  }
  mean /= static_cast<double>(a.size());
  const double deviation = std::sqrt(square / static_cast<double>(a.size()) - mean * mean);
  INFO("max |float32 - float64| = " << worst << ", field std " << deviation);
  CHECK(worst <= 1e-5 * deviation);
  block.seed = 78;
  reference::synthesize_subspace(m, 0, block, std::span<float>(b));
  CHECK(a != b);
}

TEST_CASE("a synthesized subspace image keeps the analysed image's colour statistics", "[synthesis]") {
  const AnalysisResult result = analysed_leather();
  const Material& m = result.material;
  for (std::uint32_t s = 0; s < m.subspaces.size(); ++s) {
    reference::SubspaceBlock block;
    block.seed = 3;
    block.width = block.height = 128;
    std::vector<float> image(128 * 128 * 3);
    reference::synthesize_subspace(m, s, block, std::span<float>(image));
    for (int c = 0; c < 3; ++c) {
      double mean = 0.0;
      for (std::size_t p = 0; p < 128 * 128; ++p) mean += image[p * 3 + c];
      mean /= 128.0 * 128.0;
      // The model's mean is exact in expectation. The mean of an n x n CAR field varies with standard
      // deviation sigma / (|A(0)| n), A(0) = 1 - sum(gamma) (its spectral density at frequency 0);
      // the pyramid passes frequency 0 unchanged and the colour transform mixes the bands.
      const SubspaceModel& model = m.subspaces[s];
      double variance = 0.0;
      for (std::uint32_t level = 0; level < model.levels; ++level) {
        const double n = 128.0 / std::pow(2.0, level);
        for (std::uint32_t j = 0; j < 3; ++j) {
          const CarBandModel& b = model.bands[level * 3 + j];
          double a0 = 1.0;
          for (float g : b.gamma) a0 -= g;
          const double t = model.colour_transform[c * 3 + j];
          variance += t * t * std::pow(b.sigma / (a0 * n), 2.0);
        }
      }
      const double expected = model.colour_mean[c];
      double band_means = 0.0;
      for (std::uint32_t level = 0; level < model.levels; ++level)
        for (std::uint32_t j = 0; j < 3; ++j)
          band_means += model.colour_transform[c * 3 + j] * model.bands[level * 3 + j].mean;
      INFO("subspace " << s << " channel " << c << ": synthesized mean " << mean << ", model "
                       << expected + band_means << ", standard error " << std::sqrt(variance));
      CHECK(std::abs(mean - (expected + band_means)) < 5.0 * std::sqrt(variance) + 1e-6);
    }
  }
  SECTION("interpolation at a measured pair returns that pair's subspace image") {
    std::vector<std::vector<float>> images(m.subspaces.size());
    reference::SubspaceBlock block;
    block.width = block.height = 16;
    for (std::uint32_t s = 0; s < m.subspaces.size(); ++s) {
      images[s].resize(16 * 16 * 3);
      reference::synthesize_subspace(m, s, block, std::span<float>(images[s]));
    }
    DirectionTriangulation lights, views;
    REQUIRE(build_direction_triangulation(m.lights, lights).ok());
    REQUIRE(build_direction_triangulation(m.views, views).ok());
    const PairWeights w =
        pair_weights(lights, views, m.lights[30].theta, m.lights[30].phi, m.views[70].theta, m.views[70].phi);
    std::vector<float> out(16 * 16 * 3);
    reference::interpolate_subspaces(m, w, images, out);
    CHECK(out == images[subspace_of(m, 30, 70)]);
  }
}

TEST_CASE("an analysed model keeps 12 significant bits of its colour and band numbers", "[synthesis][size]") {
  // The low mantissa bits carry only estimation noise; cleared, they deflate (material file size).
  const Material m = analysed_leather().material;
  std::size_t numbers = 0, nonzero = 0;
  auto check = [&](float v) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    INFO("value " << v);
    CHECK((bits & 0xFFFu) == 0u);
    ++numbers;
    nonzero += v != 0.0f;
  };
  for (const SubspaceModel& s : m.subspaces) {
    for (float v : s.colour_mean) check(v);
    for (float v : s.colour_transform) check(v);
    for (const CarBandModel& b : s.bands) {
      check(b.mean);
      check(b.band_std);
      check(b.sigma);
    }
  }
  CHECK(nonzero > numbers / 2);
}

TEST_CASE("block-wise synthesis from stored initialization values equals the whole synthesis",
          "[synthesis][blockwise]") {
  // 3 subspaces x 3 levels x 3 channels with 1 to 12 neighbours: frames of every pad width.
  const Material m = synthetic_material(3, 3);
  reference::SubspaceBlock whole;
  whole.seed = 2024;
  whole.row0 = -40;
  whole.col0 = 1000;
  whole.width = 150;
  whole.height = 90;
  whole.margin = 40;
  const std::vector<std::uint32_t> subspaces = {2, 0};
  const auto reference_images = reference::synthesize_subspaces(m, subspaces, whole);
  // A 2 x 2 tiling with uneven tiles, and a block at odd offsets inside.
  std::vector<reference::SubspaceBlock> blocks = test::grid_blocks(whole, {37, 53}, {71, 79});
  reference::SubspaceBlock odd = blocks[0];
  odd.row0 = whole.row0 + 17;
  odd.col0 = whole.col0 + 101;
  odd.width = 37;
  odd.height = 29;
  odd.margin = 3;  // a burn-in margin is allowed, and starts from the stored values too
  blocks.push_back(odd);
  const auto initial = reference::block_initial_values(m, subspaces, whole, blocks);
  REQUIRE(initial.size() == blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    INFO("block " << b);
    const reference::SubspaceBlock& block = blocks[b];
    const auto images = reference::synthesize_subspaces(m, subspaces, block, 0, initial[b]);
    for (std::uint32_t s : subspaces) {
      INFO("subspace " << s);
      test::require_bitwise_equal(images[s], test::crop_block(reference_images[s], whole, block, 3),
                                  std::size_t{block.width} * 3);
    }
  }
  // Without the stored values the same block starts from zeros and differs: the values carry the state.
  const auto cold = reference::synthesize_subspaces(m, subspaces, blocks[3]);
  CHECK(cold[0] != test::crop_block(reference_images[0], whole, blocks[3], 3));
  // A single subspace takes its own slice of the layout.
  std::vector<float> single(std::size_t{odd.width} * odd.height * 3);
  const std::uint32_t only0[1] = {0};
  const auto initial0 = reference::block_initial_values(m, only0, whole, std::span(&odd, 1));
  reference::synthesize_subspace(m, 0, odd, std::span<float>(single), nullptr, initial0[0]);
  test::require_bitwise_equal(single, test::crop_block(reference_images[0], whole, odd, 3));
}

TEST_CASE("block initialization values are refused where they cannot hold", "[synthesis][blockwise]") {
  const Material m = synthetic_material(1, 2);
  reference::SubspaceBlock whole;
  whole.width = whole.height = 64;
  whole.margin = 8;
  reference::SubspaceBlock outside = whole;
  outside.col0 = 60;  // past the whole's right burn-in margin
  outside.width = outside.height = 32;
  outside.margin = 0;
  CHECK_THROWS_WITH(reference::block_initial_values(m, {}, whole, std::span(&outside, 1)),
                    Catch::Contains("does not lie inside the whole synthesis"));
  reference::SubspaceBlock inside = outside;
  inside.col0 = 0;
  auto initial = reference::block_initial_values(m, {}, whole, std::span(&inside, 1));
  initial[0].pop_back();
  std::vector<float> out(32 * 32 * 3);
  CHECK_THROWS_WITH(reference::synthesize_subspace(m, 0, inside, std::span<float>(out), nullptr, initial[0]),
                    Catch::Contains("block initialization values"));
  inside.seed = 1;
  CHECK_THROWS_WITH(reference::block_initial_values(m, {}, whole, std::span(&inside, 1)),
                    Catch::Contains("seed"));
}

}  // namespace carbtf

namespace carbtf {

TEST_CASE("a synthesized subspace image keeps the measured contrast through the pyramid collapse",
          "[synthesis][calibration][slow]") {
  // Before the collapse calibration the leather sample's synthesized images kept 54-69% of the measured
  // variance in every band although each band kept its own: the loss is in the collapse.
  constexpr std::uint32_t size = 64;
  const BtfDataset dataset = rendered_sample("leather", size);
  AnalysisOptions options = small_analysis();
  options.relief_tone = false;  // the subspace images are then the measured ones, whose variance is compared
  const bool calibrated = GENERATE(true, false);
  options.calibrate_collapse = calibrated;
  const Material m = analyze_btf(dataset, options).material;
  double ratio_sum = 0.0;
  int count = 0;
  for (std::uint32_t s = 0; s < m.subspaces.size(); ++s) {
    std::vector<float> measured(dataset.pixel_count() * 3);
    dataset.linear_rgb({m.subspaces[s].light, m.subspaces[s].view}, measured);
    // A large synthesis, so that the ratio measures the model rather than sampling noise.
    reference::SubspaceBlock block;
    block.seed = 5;
    block.width = block.height = 256;
    std::vector<float> image(256 * 256 * 3);
    reference::synthesize_subspace(m, s, block, std::span<float>(image));
    auto luminance_variance = [](const std::vector<float>& rgb) {
      std::vector<double> y(rgb.size() / 3);
      for (std::size_t p = 0; p < y.size(); ++p)
        y[p] = 0.2126 * rgb[p * 3] + 0.7152 * rgb[p * 3 + 1] + 0.0722 * rgb[p * 3 + 2];
      double mean = 0.0, square = 0.0;
      for (double v : y) mean += v;
      mean /= static_cast<double>(y.size());
      for (double v : y) square += (v - mean) * (v - mean);
      return square / static_cast<double>(y.size());
    };
    const double ratio = luminance_variance(image) / luminance_variance(measured);
    INFO("subspace " << s << ": synthesized / measured luminance variance " << ratio);
    ratio_sum += ratio;
    ++count;
  }
  const double mean_ratio = ratio_sum / count;
  INFO("calibrated " << calibrated << ": mean synthesized / measured variance " << mean_ratio);
  if (calibrated) {
    CHECK(mean_ratio == Approx(1.0).margin(0.12));
  } else {
    CHECK(mean_ratio < 0.9);  // the loss the calibration repairs: without it the test above could not fail
  }
}

}  // namespace carbtf

namespace carbtf {

TEST_CASE("each subspace image takes the pyramid level count whose model looks nearest the measurement",
          "[analysis][levels][slow]") {
  // Issue 13 item 3a: fabric's weave period falls in the coarse level's band; the measure prefers two
  // levels for most of its subspace images at 256^2. Fixed, every subspace takes pyramid_levels.
  const BtfDataset dataset = rendered_sample("fabric", 128);
  AnalysisOptions options = small_analysis();
  // With a grey tone the CAR draws the weave's colours, and its period falls in the coarse level's band;
  // with the tone planes (the default) the tone draws them and 3 levels win everywhere at this size.
  options.tone_planes = TonePlanes::never;
  REQUIRE(options.pyramid_levels == 3);
  REQUIRE(options.other_level_counts == std::vector<std::uint32_t>{2});
  const auto level_counts = [](const AnalysisResult& result) {
    std::vector<std::uint32_t> levels;
    for (const SubspaceModel& s : result.material.subspaces) levels.push_back(s.levels);
    return levels;
  };
  const auto log_has = [](const AnalysisResult& result, const std::string& text) {
    return std::any_of(result.log.begin(), result.log.end(),
                       [&](const std::string& line) { return line.find(text) != std::string::npos; });
  };

  const AnalysisResult chosen = analyze_btf(dataset, options);
  const std::vector<std::uint32_t> chosen_levels = level_counts(chosen);
  INFO("levels per subspace: " << Catch::Detail::stringify(chosen_levels));
  CHECK(std::count(chosen_levels.begin(), chosen_levels.end(), 2u) >= 1);
  CHECK(std::all_of(chosen_levels.begin(), chosen_levels.end(),
                    [](std::uint32_t l) { return l == 2u || l == 3u; }));
  // 6 clamps x 2 level counts, then 6 noise gains on the finest level's bands and 6 on its chroma, 6 gains
  // and 3 raises on the coarser levels' bands, 6 gains and 7 raises on their chroma, 6 on every band and 6
  // on the chroma bands
  CHECK(log_has(chosen, "2 pyramid levels, noise gains"));
  CHECK(log_has(chosen, "chosen of 58 candidates"));

  options.other_level_counts = {};
  const AnalysisResult fixed = analyze_btf(dataset, options);
  CHECK(level_counts(fixed) == std::vector<std::uint32_t>(fixed.material.subspaces.size(), 3u));
  CHECK(log_has(fixed, "3 pyramid levels, noise gains"));
  CHECK(log_has(fixed, "chosen of 52 candidates"));
  CHECK_FALSE(log_has(fixed, "2 pyramid levels"));

  options.other_level_counts = {7};
  CHECK_THROWS_WITH(analyze_btf(dataset, options), Catch::Contains("within 1..6"));
}

}  // namespace carbtf
