// Choosing the range tiling by its look (range/range_tiling_choice.hpp): it must follow what the
// patches show, not the draw's order.
#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <random>

#include "carbtf/analysis/range/range_tiling_choice.hpp"
#include "carbtf/engine/material/range_tiles.hpp"

namespace carbtf {
namespace {

constexpr Eigen::Index kMapSize = 128;
constexpr Eigen::Index kBumpColumns = 32;  // bumps only left of this column: a quarter of the map

// Round bumps (radius 3, height 4 texels) at jittered places on an 8-texel grid, left of kBumpColumns;
// flat elsewhere.
Plane bumpy_quarter_map() {
  Plane map = Plane::Zero(kMapSize, kMapSize);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-1.5, 1.5);
  for (Eigen::Index cy = 4; cy < kMapSize; cy += 8) {
    for (Eigen::Index cx = 4; cx < kBumpColumns; cx += 8) {
      const double y0 = static_cast<double>(cy) + jitter(rng), x0 = static_cast<double>(cx) + jitter(rng);
      for (Eigen::Index r = 0; r < kMapSize; ++r) {
        for (Eigen::Index c = 0; c < kBumpColumns + 4; ++c) {
          const double d2 = (static_cast<double>(r) - y0) * (static_cast<double>(r) - y0) +
                            (static_cast<double>(c) - x0) * (static_cast<double>(c) - x0);
          if (d2 < 9.0) map(r, c) = std::max(map(r, c), 4.0 * std::sqrt(1.0 - d2 / 9.0));
        }
      }
    }
  }
  return map;
}

// The share of an enlargement's texels (the map's size, layouts 1 and 2) on a bump.
double bump_share(const RangeTiles& tiles) {
  double on = 0.0, all = 0.0;
  for (const std::uint64_t layout : {1u, 2u}) {
    std::vector<float> heights(std::size_t{kMapSize} * kMapSize);
    enlarge_range_map(tiles, {layout, 0, 0, kMapSize, kMapSize, 0}, heights);
    for (const float h : heights) on += h > 0.5f ? 1.0 : 0.0;
    all += static_cast<double>(heights.size());
  }
  return on / all;
}

RangeTileOptions small_tiles(std::uint64_t seed) {
  RangeTileOptions options;
  options.tile_size = 64;
  options.seed = seed;
  return options;
}

}  // namespace

TEST_CASE("the range tiling choice keeps the draw whose patches show the map's relief, in either order",
          "[range]") {
  const Plane map = bumpy_quarter_map();
  const double whole = static_cast<double>((map > 0.5).count()) / static_cast<double>(map.size());
  REQUIRE(whole > 0.1);
  // Base seeds whose two draws differ clearly in how much of the relief they show: one whose first
  // draw shows it, one whose second does.
  std::optional<std::uint64_t> first_better, second_better;
  for (std::uint64_t base = 1; base <= 200 && !(first_better && second_better); ++base) {
    const double error0 =
        std::abs(bump_share(build_range_tiles(map, small_tiles(tiling_candidate_seed(base, 0)))) - whole);
    const double error1 =
        std::abs(bump_share(build_range_tiles(map, small_tiles(tiling_candidate_seed(base, 1)))) - whole);
    if (error0 < 0.25 * whole && error1 > 0.75 * whole) first_better = first_better.value_or(base);
    if (error1 < 0.25 * whole && error0 > 0.75 * whole) second_better = second_better.value_or(base);
  }
  REQUIRE(first_better);
  REQUIRE(second_better);
  const ReliefLook look{0.1, 0.0};
  const RangeTilingChoice a = choose_range_tiling(map, small_tiles(*first_better), {}, look, 2, 1);
  const RangeTilingChoice b = choose_range_tiling(map, small_tiles(*second_better), {}, look, 2, 1);
  CHECK(a.chosen == 0);
  CHECK(b.chosen == 1);
  CHECK(a.distances[0] < a.distances[1]);
  CHECK(b.distances[1] < b.distances[0]);
  CHECK(b.seed == tiling_candidate_seed(*second_better, 1));
}

TEST_CASE("one range tiling candidate is the tile builder's own draw, unscored", "[range]") {
  const Plane map = bumpy_quarter_map();
  const RangeTiles built = build_range_tiles(map, small_tiles(7));
  const RangeTilingChoice one = choose_range_tiling(map, small_tiles(7), {}, {0.1, 0.0}, 1, 1);
  CHECK(one.chosen == 0);
  CHECK(one.seed == 7);
  CHECK(one.tiles.patches == built.patches);
  CHECK(one.tiles.cuts == built.cuts);
  CHECK(one.distances == std::vector<double>{0.0});
  CHECK_THROWS_AS(choose_range_tiling(map, small_tiles(7), {}, {0.1, 0.0}, 0, 1), std::invalid_argument);
}

}  // namespace carbtf
