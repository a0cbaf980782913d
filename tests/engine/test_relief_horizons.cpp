// The relief's horizons and the share of a light they leave (relief_horizons.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "carbtf/engine/render/relief_horizons.hpp"

using namespace carbtf;
using Catch::Matchers::WithinAbs;

namespace {

// A flat 32 x 16 field with a wall 3 texels high on columns 20..23 (rows all).
std::vector<float> wall_field() {
  std::vector<float> h(32 * 16, 0.0f);
  for (std::uint32_t r = 0; r < 16; ++r)
    for (std::uint32_t c = 20; c < 24; ++c) h[r * 32 + c] = 3.0f;
  return h;
}

std::span<const float, kReliefHorizonDirections> at(const std::vector<float>& horizons, std::uint32_t row,
                                                    std::uint32_t col) {
  return std::span<const float, kReliefHorizonDirections>(
      &horizons[(row * 32 + col) * kReliefHorizonDirections], kReliefHorizonDirections);
}

}  // namespace

TEST_CASE("horizons: a wall rises 3 texels over the flat floor in front of it", "[render][shadows]") {
  std::vector<float> horizons;
  relief_horizons(wall_field(), 32, 16, false, 1.0f, horizons);
  REQUIRE(horizons.size() == 32 * 16 * kReliefHorizonDirections);
  // Column 17, 3 texels before the wall along +x: tangent 3 / 3; the diagonals reach it 3 steps of
  // sqrt 2 away: 3 / (3 sqrt 2); along -x, +y and -y the floor is flat: 0.
  const auto h = at(horizons, 8, 17);
  CHECK_THAT(h[0], WithinAbs(1.0, 1e-6));
  CHECK_THAT(h[1], WithinAbs(1.0 / std::sqrt(2.0), 1e-6));
  CHECK_THAT(h[7], WithinAbs(1.0 / std::sqrt(2.0), 1e-6));
  CHECK(h[2] == 0.0f);
  CHECK(h[4] == 0.0f);
  CHECK(h[6] == 0.0f);
  // Beyond the reach the wall is not seen; on top of it nothing rises.
  CHECK(at(horizons, 8, 20 - kReliefHorizonReach - 1)[0] == 0.0f);
  for (float v : at(horizons, 8, 21)) CHECK(v == 0.0f);
  // The scale multiplies the heights, so the tangents.
  std::vector<float> half;
  relief_horizons(wall_field(), 32, 16, false, 0.5f, half);
  CHECK_THAT(at(half, 8, 17)[0], WithinAbs(0.5, 1e-6));
}

TEST_CASE("horizons: periodic fields see across the edge, plain ones repeat the edge texel",
          "[render][shadows]") {
  // A ridge 2 texels high on the last column.
  std::vector<float> edge(32 * 16, 0.0f);
  for (std::uint32_t r = 0; r < 16; ++r) edge[r * 32 + 31] = 2.0f;
  std::vector<float> plain, periodic;
  relief_horizons(edge, 32, 16, false, 1.0f, plain);
  relief_horizons(edge, 32, 16, true, 1.0f, periodic);
  CHECK(at(plain, 4, 1)[4] == 0.0f);                        // -x: column 0 repeated, flat
  CHECK_THAT(at(periodic, 4, 1)[4], WithinAbs(1.0, 1e-6));  // -x: column 31 two texels away across the edge
  CHECK_THAT(at(plain, 4, 29)[0], WithinAbs(1.0, 1e-6));    // +x: the ridge itself, either way
  CHECK_THAT(at(periodic, 4, 29)[0], WithinAbs(1.0, 1e-6));
}

TEST_CASE("visibility: a light above the horizon is seen, below it hidden, with a penumbra between",
          "[render][shadows]") {
  std::vector<float> horizons;
  relief_horizons(wall_field(), 32, 16, false, 1.0f, horizons);
  const auto h = at(horizons, 8, 17);  // horizon tangent 1 towards +x, 0 towards -x
  auto light = [](float elevation_degrees, float azimuth_degrees) {
    const float e = elevation_degrees * 3.14159265f / 180.0f, a = azimuth_degrees * 3.14159265f / 180.0f;
    return std::array<float, 3>{std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
  };
  CHECK(relief_visibility(h, light(60.0f, 0.0f)) == 1.0f);  // tangent 1.73 above 1 + half the penumbra
  CHECK(relief_visibility(h, light(30.0f, 0.0f)) == 0.0f);  // tangent 0.58 below 1 - half of it
  CHECK_THAT(relief_visibility(h, light(45.0f, 0.0f)), WithinAbs(0.5, 1e-5));  // on the horizon
  CHECK(relief_visibility(h, light(30.0f, 180.0f)) == 1.0f);                   // from the open side
  CHECK(relief_visibility(h, {0.0f, 0.0f, 1.0f}) == 1.0f);                     // overhead
  // Between the azimuths 0 and 45 degrees (horizons 1 and 1/sqrt 2) the horizon is interpolated:
  // at 22.5 degrees about 0.854, so a light at tangent 0.854 sits on it.
  const float mid = 0.5f * (1.0f + 1.0f / std::sqrt(2.0f));
  const float across = 1.0f / std::sqrt(1.0f + mid * mid);
  const float a = 22.5f * 3.14159265f / 180.0f;
  CHECK_THAT(relief_visibility(h, {across * std::cos(a), across * std::sin(a), across * mid}),
             WithinAbs(0.5, 1e-4));
}
