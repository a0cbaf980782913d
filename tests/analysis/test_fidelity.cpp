// Fidelity measures (DESIGN.md 5): zero for identical images, small for two realizations of one random
// field, and each one responsive to the property it measures.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "carbtf/analysis/quality/fidelity.hpp"

namespace carbtf {
namespace {

// A grey-ish linear RGB image: base + contrast * field, where the field is white noise, optionally
// smoothed by a box filter of half-width `blur` (wrapping), seeded.
std::vector<float> noise_image(std::uint32_t size, std::uint32_t seed, float base, float contrast,
                               int blur = 0) {
  std::mt19937 engine(seed);
  std::normal_distribution<float> normal;
  std::vector<float> field(std::size_t{size} * size);
  for (float& v : field) v = normal(engine);
  if (blur > 0) {
    std::vector<float> smooth(field.size(), 0.0f);
    const int n = static_cast<int>(size);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        float sum = 0.0f;
        for (int dr = -blur; dr <= blur; ++dr)
          for (int dc = -blur; dc <= blur; ++dc)
            sum += field[std::size_t((r + dr + n) % n) * size + std::size_t((c + dc + n) % n)];
        smooth[std::size_t(r) * size + std::size_t(c)] =
            sum / static_cast<float>(2 * blur + 1);  // unit-ish std
      }
    field = smooth;
  }
  std::vector<float> rgb(field.size() * 3);
  for (std::size_t p = 0; p < field.size(); ++p) {
    const float v = std::max(0.0f, base + contrast * field[p]);
    rgb[p * 3] = v;
    rgb[p * 3 + 1] = 0.9f * v;
    rgb[p * 3 + 2] = 0.8f * v;
  }
  return rgb;
}

}  // namespace

TEST_CASE("fidelity of an image against itself is zero", "[fidelity]") {
  const auto image = noise_image(64, 1, 0.3f, 0.05f);
  const FidelityError e = fidelity_error(image, 64, 64, image, 64, 64);
  CHECK(e.delta_e == 0.0);
  CHECK(e.std_relative == 0.0);
  CHECK(e.spectrum_l1 == 0.0);
  CHECK(e.histogram_w1 == 0.0);
}

TEST_CASE("two realizations of one field, even of different sizes, are close", "[fidelity]") {
  // Lightly correlated fields of 256^2 and 192^2: their mean L* differ by sampling noise of about 0.1.
  const auto a = noise_image(256, 1, 0.3f, 0.05f, 1);
  const auto b = noise_image(192, 2, 0.3f, 0.05f, 1);
  const FidelityError e = fidelity_error(a, 256, 256, b, 192, 192);
  INFO(e.delta_e << " " << e.std_relative << " " << e.spectrum_l1 << " " << e.histogram_w1);
  CHECK(e.delta_e < 0.3);
  CHECK(e.std_relative < 0.05);
  CHECK(e.spectrum_l1 < 0.15);
  CHECK(e.histogram_w1 < 0.5);
}

TEST_CASE("each fidelity measure responds to its own property", "[fidelity]") {
  const auto measured = noise_image(128, 1, 0.3f, 0.05f, 2);
  const FidelityError same =
      fidelity_error(noise_image(128, 2, 0.3f, 0.05f, 2), 128, 128, measured, 128, 128);
  SECTION("a brighter model: colour and distribution, not structure") {
    const FidelityError e =
        fidelity_error(noise_image(128, 2, 0.45f, 0.05f, 2), 128, 128, measured, 128, 128);
    INFO(e.delta_e << " " << e.histogram_w1 << " " << e.spectrum_l1);
    CHECK(e.delta_e > 5.0);
    CHECK(e.histogram_w1 > 2.0);
    CHECK(e.spectrum_l1 < same.spectrum_l1 + 0.1);
  }
  SECTION("double the contrast: the std") {
    const FidelityError e = fidelity_error(noise_image(128, 2, 0.3f, 0.1f, 2), 128, 128, measured, 128, 128);
    INFO(e.std_relative);
    // L* is concave in luminance, so doubling the linear contrast does not exactly double the L* std.
    CHECK(e.std_relative > 0.7);
    CHECK(e.std_relative > 10 * same.std_relative);
    CHECK(e.spectrum_l1 < same.spectrum_l1 + 0.1);
  }
  SECTION("white noise against a smooth field: the spectrum") {
    const FidelityError e = fidelity_error(noise_image(128, 2, 0.3f, 0.05f), 128, 128, measured, 128, 128);
    INFO(e.spectrum_l1 << " against " << same.spectrum_l1);
    CHECK(e.spectrum_l1 > 5 * same.spectrum_l1);
    CHECK(e.spectrum_l1 > 0.3);
  }
}

TEST_CASE("fidelity refuses images too small", "[fidelity]") {
  const std::vector<float> one(3, 0.5f);
  CHECK_THROWS_AS(fidelity_error(one, 1, 1, one, 1, 1), std::invalid_argument);
  const std::vector<float> short_buffer(5, 0.5f);
  CHECK_THROWS_AS(fidelity_error(short_buffer, 2, 2, short_buffer, 2, 2), std::invalid_argument);
}

}  // namespace carbtf
