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

// Mean absolute height step between neighbouring texels of the composed tiles, over the pairs a cut
// separates and over the rest.
struct JoinSteps {
  double across = 0.0;
  double elsewhere = 0.0;
};
JoinSteps join_steps(const RangeTiles& tiles) {
  const std::uint32_t size = tiles.tile_size, half = size / 2;
  const std::vector<float> all = composed_tiles(tiles);
  double sum[2] = {0, 0};
  std::size_t count[2] = {0, 0};
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    const float* tile = all.data() + std::size_t{t} * size * size;
    for (std::uint32_t q = 0; q < 4; ++q) {
      const auto quadrant = static_cast<TileQuadrant>(q);
      const std::uint16_t* cut = tiles.cuts.data() + (std::size_t{t} * 4 + q) * half;
      auto add = [&](std::uint32_t u0, std::uint32_t v0, std::uint32_t u1, std::uint32_t v1) {
        std::uint32_t x0, y0, x1, y1;
        quadrant_to_tile(size, quadrant, u0, v0, x0, y0);
        quadrant_to_tile(size, quadrant, u1, v1, x1, y1);
        const int across = (u0 < cut[v0]) != (u1 < cut[v1]) ? 0 : 1;
        sum[across] += std::abs(double{tile[y0 * size + x0]} - tile[y1 * size + x1]);
        ++count[across];
      };
      for (std::uint32_t v = 0; v < half; ++v) {
        for (std::uint32_t u = 0; u < half; ++u) {
          if (u + 1 < half) add(u, v, u + 1, v);
          if (v + 1 < half) add(u, v, u, v + 1);
        }
      }
    }
  }
  return {sum[0] / count[0], sum[1] / count[1]};
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
  const JoinSteps before = join_steps(hard), after = join_steps(feathered);
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
