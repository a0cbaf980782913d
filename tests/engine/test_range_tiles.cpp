// Range-tile joins (range_tiles.hpp): a feathered cut cross-fades its two patches, so a join shows no
// step at grazing light, changes nothing where the patches agree, and survives the file's filling of
// the texels no tile reads.
#include <catch2/catch.hpp>

#include <cmath>

#include "carbtf/engine/material/range_tiles.hpp"
#include "test_range_tiles.hpp"

using namespace carbtf;

namespace {

std::vector<float> composed_tiles(const RangeTiles& tiles) {
  const std::size_t texels = std::size_t{tiles.tile_size} * tiles.tile_size;
  std::vector<float> all(texels * range_tile_count(tiles));
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t)
    compose_range_tile(tiles, t, std::span<float>(all).subspan(t * texels, texels));
  return all;
}

double smooth_relief(std::uint32_t r, std::uint32_t c) {
  return 4 * std::sin(r / 6.0) * std::cos(c / 9.0) + 0.05 * ((r * 7 + c * 13) % 11);
}

}  // namespace

TEST_CASE("feathered cuts turn a join's step into a ramp as gentle as the relief", "[range_tiles]") {
  test::WindowedTileOptions options;
  options.map_rows = options.map_cols = 96;
  options.tile_size = 32;
  options.height_bits = 10;
  const RangeTiles hard = test::windowed_range_tiles(smooth_relief, {}, options);
  options.feather = 1;
  const RangeTiles feathered = test::windowed_range_tiles(smooth_relief, {}, options);
  const JoinSteps before = measure_join_steps(hard), after = measure_join_steps(feathered);
  INFO("hard cuts: across " << before.across << ", elsewhere " << before.elsewhere << "; feathered: across "
                            << after.across << ", elsewhere " << after.elsewhere);
  // Windows from different places of the map disagree at the cuts: a hard cut steps there. These cuts
  // are straight diagonals, not the analysis's least-difference ones, so the steps are large; a 3-texel
  // ramp takes each in three parts.
  CHECK(before.across > 2.0 * before.elsewhere);
  CHECK(after.across < 0.4 * before.across);
}

TEST_CASE("a feathered cut changes nothing where its patches agree and keeps what it reads when filled",
          "[range_tiles]") {
  test::WindowedTileOptions options;
  options.map_rows = options.map_cols = 64;
  options.feather = 1;
  RangeTiles tiles = test::windowed_range_tiles(smooth_relief, {}, options);
  // Every patch the top-left half-tile block of the first, repeated: patches in their edge roles are
  // shifted by half a tile, so then every tile texel reads the same value from both, and the
  // cross-fade of equal values is that value.
  const std::uint32_t size = tiles.tile_size, half = size / 2;
  const std::size_t texels = std::size_t{size} * size;
  RangeTiles same = tiles;
  for (std::size_t p = 0; p < same.patches.size() / texels; ++p) {
    for (std::uint32_t r = 0; r < size; ++r) {
      for (std::uint32_t c = 0; c < size; ++c)
        same.patches[p * texels + std::size_t{r} * size + c] =
            tiles.patches[std::size_t{r % half} * size + c % half];
    }
  }
  same.feather = 0;
  const std::vector<float> hard = composed_tiles(same);
  same.feather = 1;
  const std::vector<float> soft = composed_tiles(same);
  REQUIRE(hard.size() == soft.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < hard.size(); ++i) worst = std::max(worst, std::abs(double{hard[i]} - soft[i]));
  CHECK(worst <= 1e-5 * tiles.height_scale * 1023);

  // The file's filling of unread texels (predicted values, nearly free to store) keeps every texel
  // the cross-fade reads: the composed tiles stay the same, value for value.
  const std::vector<float> before = composed_tiles(tiles);
  fill_unseen_patch_texels(tiles);
  CHECK(composed_tiles(tiles) == before);
}
