// The relief's specular lobe in the analysis (model/relief_specular.hpp): fitted to the images of a
// rendered sample whose renderer adds a Blinn-Phong lobe over its true heights, it is kept with about
// the renderer's strength and gloss, and fitted in turn with the tone it comes nearer still; the same
// sample without the lobe gets none.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/model/relief_specular.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "test_top_view.hpp"

namespace carbtf {

using test::heights_of;
using test::top_view_dataset;

namespace {

// The top view of built-in sample `name` (64^2, seed 3) whose renderer adds a lobe of `specular` and
// `gloss`, and its true heights.
struct GlossySample {
  Surface surface;
  Plane heights;
  BtfDataset dataset;
};
GlossySample glossy_sample(const std::string& name, float specular, float gloss) {
  Surface surface = make_sample_surface(name, 64, 3);
  surface.specular = specular;
  surface.gloss = gloss;
  const Plane heights = heights_of(surface);
  BtfDataset dataset = top_view_dataset(surface);
  return {std::move(surface), heights, std::move(dataset)};
}

// The renderer's lobe strength: irradiance * N.L * specular * (gloss + 8) / (8 pi) * (N.H)^gloss.
double renderer_lobe_strength(const Surface& surface) {
  return RenderOptions{}.irradiance * surface.specular * (surface.gloss + 8.0) / (8.0 * std::numbers::pi);
}

// The lobe fitted once, against the tone of the sample's images as they are.
SpecularFit single_fit(const GlossySample& s) {
  const double z_floor = test::kTopViewLightZFloor;
  return fit_relief_specular(s.dataset, 0, s.heights, relief_tone(s.dataset, 0, s.heights, z_floor), z_floor);
}

}  // namespace

TEST_CASE("a relief's specular lobe is fitted with about the renderer's strength and gloss",
          "[tone][specular]") {
  const GlossySample sample = glossy_sample("fabric", 0.06f, 16.0f);
  const SpecularFit fit = single_fit(sample);
  const double truth = renderer_lobe_strength(sample.surface);
  INFO("strength " << fit.lobe.strength << " (renderer " << truth << "), gloss " << fit.lobe.gloss
                   << ": error " << fit.error << ", without the lobe " << fit.error_without);
  CHECK(fit.error <= (1.0 - kSpecularFitGain) * fit.error_without);
  CHECK(fit.lobe.strength > truth / 1.5);
  CHECK(fit.lobe.strength < truth * 1.5);
  CHECK(std::abs(std::log2(fit.lobe.gloss / sample.surface.gloss)) <= 1.0);
}

TEST_CASE("fitted in turn with the tone, the lobe explains the images better and nears the renderer's",
          "[tone][specular]") {
  const GlossySample sample = glossy_sample("leather", 0.06f, 16.0f);
  const std::vector<SpecularFit> rounds =
      fit_relief_specular_with_tone(sample.dataset, 0, sample.heights, test::kTopViewLightZFloor);
  const double truth = renderer_lobe_strength(sample.surface);
  REQUIRE(rounds.size() == 1 + kSpecularToneRounds);
  // The first round is the fit against the tone of the images as they are.
  const SpecularFit first = single_fit(sample);
  CHECK(rounds.front().lobe.strength == first.lobe.strength);
  CHECK(rounds.front().lobe.gloss == first.lobe.gloss);
  for (std::size_t r = 0; r < rounds.size(); ++r) {
    INFO("round " << r << ": strength " << rounds[r].lobe.strength << " (renderer " << truth << "), gloss "
                  << rounds[r].lobe.gloss << ", error " << rounds[r].error);
    CHECK(rounds[r].lobe.strength > 0.0);
    if (r > 0) CHECK(rounds[r].error < rounds[r - 1].error);
  }
  INFO("strength " << first.lobe.strength << " -> " << rounds.back().lobe.strength << " (renderer " << truth
                   << ")");
  CHECK(std::abs(std::log(rounds.back().lobe.strength / truth)) <
        std::abs(std::log(first.lobe.strength / truth)));
}

TEST_CASE("a relief without highlights gets no specular lobe", "[tone][specular]") {
  const SpecularFit fit = single_fit(glossy_sample("fabric", 0.0f, 16.0f));
  INFO("strength " << fit.lobe.strength << ", gloss " << fit.lobe.gloss << ": error " << fit.error
                   << ", without " << fit.error_without);
  CHECK(fit.lobe.strength == 0.0);
  CHECK(fit.error == fit.error_without);
}

TEST_CASE("the specular lobe peaks where the facet faces the half vector", "[tone][specular]") {
  // A ramp rising along +x: every facet's normal leans towards -x.
  Plane ramp(8, 8);
  for (Eigen::Index r = 0; r < 8; ++r)
    for (Eigen::Index c = 0; c < 8; ++c) ramp(r, c) = 0.3 * static_cast<double>(c);
  const double tilt = std::atan(0.3);
  const std::array<double, 3> top{0.0, 0.0, 1.0};
  // Mirror of the view about the facet normal: the lobe is N.L there, its peak value.
  const std::array<double, 3> mirror{-std::sin(2.0 * tilt), 0.0, std::cos(2.0 * tilt)};
  const Plane peak = specular_lobe(ramp, mirror, top, 32.0);
  CHECK(peak(4, 4) == Approx(std::cos(tilt)).epsilon(1e-9));
  const std::array<double, 3> other_side{std::sin(2.0 * tilt), 0.0, std::cos(2.0 * tilt)};
  CHECK(specular_lobe(ramp, other_side, top, 32.0)(4, 4) < 0.01 * peak(4, 4));
  CHECK(lobe_of({}, ramp, mirror, top).isZero());
  CHECK(lobe_of({2.0, 32.0}, ramp, mirror, top)(4, 4) == Approx(2.0 * peak(4, 4)));
}

TEST_CASE("the lobe grows with the view's tilt as the render pass draws it", "[tone][specular]") {
  Plane ramp(8, 8);
  for (Eigen::Index r = 0; r < 8; ++r)
    for (Eigen::Index c = 0; c < 8; ++c) ramp(r, c) = 0.3 * static_cast<double>(c);
  // The top view, one 60 degrees from the normal (z 0.5) and one beyond the floor (z 0.1), lit from above.
  for (const double z : {1.0, 0.5, 0.1}) {
    const std::array<double, 3> view{-std::sqrt(1.0 - z * z), 0.0, z};
    const std::array<double, 3> light{0.0, 0.0, 1.0};
    const Plane same = lobe_of({2.0, 8.0, 0.0}, ramp, light, view);
    const double expected_gain = std::pow(std::max(z, double{kSpecularViewFloor}), -0.5);
    REQUIRE(same(4, 4) > 0.0);
    CHECK(lobe_of({2.0, 8.0, 0.5}, ramp, light, view)(4, 4) == Approx(expected_gain * same(4, 4)));
    CHECK(lobe_of({2.0, 8.0, 0.5}, ramp, light, view)(4, 4) ==
          Approx(specular_view_gain(0.5f, static_cast<float>(z)) * same(4, 4)).epsilon(1e-6));
  }
}

}  // namespace carbtf
