// The material file's deflated chunks and the filters before zlib (chunk_filters.hpp): exact read back,
// lying sizes refused before they cost, the raster predictor, the window filter and patch filling.
#include <catch2/catch.hpp>

#include "material_file_samples.hpp"

namespace carbtf {

using namespace material_file_samples;

TEST_CASE("deflated chunks read back exactly, and a lying one is refused before it costs",
          "[material_file][deflate]") {
  const Material m = sample_material();
  REQUIRE_FALSE(m.range.tone.empty());
  const std::vector<std::uint8_t> plain = encoded(m), packed = deflated(m);
  CHECK(packed.size() < plain.size());
  const std::string defl = "DEFL";
  CHECK(std::search(packed.begin(), packed.end(), defl.begin(), defl.end()) != packed.end());
  CHECK(std::search(plain.begin(), plain.end(), defl.begin(), defl.end()) == plain.end());
  for (const auto* bytes : {&plain, &packed}) {
    Material back;
    REQUIRE(decode_material(*bytes, "x.cbtf", back).ok());
    CHECK(back == m);
  }

  auto refused = [](std::vector<std::uint8_t> bytes) {
    fix_crcs(bytes);
    Material back;
    const Status s = decode_material(bytes, "bad.cbtf", back);
    REQUIRE_FALSE(s.ok());
    return s.message();
  };
  const auto first = static_cast<std::size_t>(
      std::search(packed.begin(), packed.end(), defl.begin(), defl.end()) - packed.begin());
  const std::size_t size_at = first + 8 + 4;  // after the tag, the chunk size and the inner tag
  SECTION("a claimed size far beyond what the stream can hold") {
    auto bytes = packed;
    for (int i = 0; i < 4; ++i) bytes[size_at + i] = 0xFF;
    CHECK_THAT(refused(bytes), Catch::Contains("bad.cbtf: deflated chunk claims 4294967295 inflated bytes"));
  }
  SECTION("a claimed size one byte off") {
    auto bytes = packed;
    bytes[size_at] = static_cast<std::uint8_t>(bytes[size_at] + 1);
    CHECK_THAT(refused(bytes), Catch::Contains("does not inflate to its"));
  }
  SECTION("a damaged stream behind a valid CRC") {
    auto bytes = packed;
    bytes[size_at + 4 + 1 + 3] ^= 0x5A;
    CHECK_THAT(refused(bytes), Catch::Contains("bad.cbtf: deflated chunk"));
  }
  SECTION("a deflated chunk inside a deflated chunk") {
    auto bytes = packed;
    std::copy(defl.begin(), defl.end(), bytes.begin() + static_cast<std::ptrdiff_t>(first + 8));
    CHECK_THAT(refused(bytes), Catch::Contains("holds another deflated chunk"));
  }
}

TEST_CASE("heights and tone are stored as residuals of a raster predictor and read back exactly",
          "[material_file][deflate][raster]") {
  const std::vector<std::uint8_t> packed = deflated_round_trip(patch_filled_material());
  CHECK(packed[6] == kMaterialFormatMinor);
  // The encoder keeps the smallest filter; on a smooth relief that is the raster filter (9) for both.
  const std::size_t range_at = deflated_chunk_at(packed, "RNGE");
  const std::size_t tone_at = deflated_chunk_at(packed, "TONE");
  REQUIRE(range_at != std::string::npos);
  REQUIRE(tone_at != std::string::npos);
  CHECK(packed[range_at + 16] == 9);
  CHECK(packed[range_at + 21] == 2);  // 2-byte heights
  CHECK(packed[tone_at + 16] == 9);
  CHECK(packed[tone_at + 21] == 1);  // 1-byte tone

  auto refused = [&](std::size_t at, std::uint32_t value, int width) {
    return refused_with(packed, at, value, width);
  };
  SECTION("an unknown filter") {
    CHECK_THAT(refused(range_at + 16, 11, 1),
               Catch::Contains("bad.cbtf: deflated chunk has unknown filter 11"));
  }
  SECTION("3-byte values") {
    CHECK_THAT(refused(range_at + 21, 3, 1), Catch::Contains("raster filter that does not fit"));
  }
  SECTION("rasters whose size overflows 64 bits") {
    std::vector<std::uint8_t> bytes = packed;
    for (std::size_t k = 22; k < 34; ++k) bytes[range_at + k] = 0xFF;  // width, height and count 2^32 - 1
    fix_crcs(bytes);
    Material damaged;
    const Status s = decode_material(bytes, "bad.cbtf", damaged);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.message(), Catch::Contains("raster filter that does not fit"));
  }
  SECTION("rasters past the payload's end") {
    CHECK_THAT(refused(range_at + 30, 1000, 4), Catch::Contains("raster filter that does not fit"));
  }
  SECTION("a skip past the payload's end") {
    CHECK_THAT(refused(range_at + 17, 0xFFFFFFF0u, 4), Catch::Contains("raster filter that does not fit"));
  }
  SECTION("a rest stride beyond 8") {
    CHECK_THAT(refused(range_at + 34, 9, 1), Catch::Contains("rest stride 9"));
  }
}

TEST_CASE("patches cut from overlapping places of one map are stored once (the window filter)",
          "[material_file][deflate][raster]") {
  const std::vector<std::uint8_t> packed = deflated_round_trip(rough_relief_material());
  const std::size_t range_at = deflated_chunk_at(packed, "RNGE");
  const std::size_t tone_at = deflated_chunk_at(packed, "TONE");
  REQUIRE(range_at != std::string::npos);
  REQUIRE(tone_at != std::string::npos);
  CHECK(packed[range_at + 16] == 10);
  CHECK(packed[tone_at + 16] == 10);
  // The same tiles filled patch by patch cannot share the texels one patch shows and another does not,
  // so they fall back to the raster filter and take more room.
  const std::vector<std::uint8_t> per_patch = deflated(rough_relief_material(true));
  CHECK(per_patch[deflated_chunk_at(per_patch, "RNGE") + 16] == 9);
  CHECK(static_cast<double>(packed.size()) < 0.9 * static_cast<double>(per_patch.size()));

  const auto u32_at = [&](std::size_t at) {
    return static_cast<std::uint32_t>(packed[at]) | static_cast<std::uint32_t>(packed[at + 1]) << 8 |
           static_cast<std::uint32_t>(packed[at + 2]) << 16 |
           static_cast<std::uint32_t>(packed[at + 3]) << 24;
  };
  const std::size_t source_at = range_at + 35;  // after the raster filter's parameters
  const std::uint32_t source_width = u32_at(source_at);
  const std::uint32_t source_height = u32_at(source_at + 4);
  CHECK(std::uint64_t{source_width} * source_height < 4u * 32u * 32u);
  auto refused = [&](std::size_t at, std::uint32_t value) { return refused_with(packed, at, value, 4); };
  SECTION("a window past the source's right edge") {
    CHECK_THAT(refused(source_at + 8, source_width - 31),
               Catch::Contains("bad.cbtf: deflated chunk has a window placement outside its"));
  }
  SECTION("a window past the source's bottom edge, by 2^32") {
    CHECK_THAT(refused(source_at + 12, 0xFFFFFFFFu), Catch::Contains("window placement outside"));
  }
  SECTION("a source larger than the rasters it replaces") {
    CHECK_THAT(refused(source_at, 0x10000u), Catch::Contains("a source larger than its rasters"));
  }
  SECTION("a source that does not match its stream") {
    CHECK_THAT(refused(source_at + 4, source_height - 1), Catch::Contains("bad.cbtf: deflated chunk"));
  }
}

TEST_CASE("patches that agree almost everywhere are encoded within bounded work",
          "[material_file][deflate][raster]") {
  // Every offset of these patches agrees until the last texel, which defeats the window search's early
  // exits; its work bound makes it give up, and the file is still exact.
  Material m = sample_material();
  RangeTiles& r = m.range;
  r.tile_size = 256;
  const std::size_t texels = std::size_t{r.tile_size} * r.tile_size;
  r.patches.assign(4 * texels, 7);
  for (std::size_t p = 0; p < 4; ++p) r.patches[(p + 1) * texels - 1] = static_cast<std::uint16_t>(8 + p);
  r.tone.assign(r.patches.size(), 3);
  r.cuts.assign(std::size_t{range_tile_count(r)} * 4 * (r.tile_size / 2), 1);
  for (std::size_t i = r.tile_size / 2 - 1; i < r.cuts.size(); i += r.tile_size / 2)
    r.cuts[i] = static_cast<std::uint16_t>(r.tile_size / 2);
  for (std::size_t i = 0; i < r.cuts.size(); i += r.tile_size / 2) r.cuts[i] = 0;
  REQUIRE(validate_material(m).ok());
  deflated_round_trip(m);
}

TEST_CASE("patch texels that no tile shows are filled so they cost nothing and no tile changes",
          "[material_file][raster]") {
  const Material filled = patch_filled_material();
  const RangeTiles& tiles = filled.range;
  const std::size_t tile_texels = std::size_t{tiles.tile_size} * tiles.tile_size;
  auto composed = [&](const RangeTiles& t, RangeChannel channel) {
    std::vector<float> all(tile_texels * range_tile_count(t));
    for (std::uint32_t i = 0; i < range_tile_count(t); ++i)
      compose_range_tile(t, i, std::span<float>(all).subspan(i * tile_texels, tile_texels), channel);
    return all;
  };
  const std::vector<bool> shown = shown_patch_texels(tiles);
  const auto unseen = static_cast<std::size_t>(std::count(shown.begin(), shown.end(), false));
  CHECK(unseen > tiles.patches.size() / 5);
  CHECK(unseen < tiles.patches.size());

  // The same tiles before filling: random values where no tile looks.
  Material unfilled = filled;
  std::mt19937 rng(5);
  for (std::size_t i = 0; i < shown.size(); ++i) {
    if (shown[i]) continue;
    unfilled.range.patches[i] = static_cast<std::uint16_t>(rng() % 512);
    unfilled.range.tone[i] = static_cast<std::uint8_t>(rng() % 256);
  }
  REQUIRE(unfilled.range != filled.range);
  RangeTiles refilled = unfilled.range;
  fill_unseen_patch_texels(refilled);
  CHECK(refilled == tiles);  // only the shown texels decide the filling
  for (RangeChannel channel : {RangeChannel::height, RangeChannel::tone})
    CHECK(composed(unfilled.range, channel) == composed(tiles, channel));
  CHECK(deflated(filled).size() < deflated(unfilled).size());
}

TEST_CASE("windows of one map are filled as one map and show the same tiles", "[material_file][raster]") {
  const Material windows = smooth_relief_material();
  const Material patches = patch_filled_material();
  const RangeTiles& tiles = windows.range;
  REQUIRE(tiles.patches != patches.range.patches);
  const std::size_t tile_texels = std::size_t{tiles.tile_size} * tiles.tile_size;
  for (RangeChannel channel : {RangeChannel::height, RangeChannel::tone}) {
    for (std::uint32_t i = 0; i < range_tile_count(tiles); ++i) {
      std::vector<float> a(tile_texels), b(tile_texels);
      compose_range_tile(tiles, i, a, channel);
      compose_range_tile(patches.range, i, b, channel);
      CHECK(a == b);
    }
  }
  SECTION("windows that do not match the patches fall back to filling each patch") {
    RangeTiles refilled = tiles;
    const std::vector<PatchWindow> too_few{{0, 0}, {4, 4}};
    fill_unseen_patch_texels(refilled, too_few);
    CHECK(refilled == patches.range);
  }
}

TEST_CASE("a format 1.0 file (plain chunks, no relief tone) still reads", "[material_file][compatibility]") {
  Material m = sample_material();
  m.range.tone.clear();
  m.range.tone_offset = m.range.tone_scale = 0.0f;
  std::vector<std::uint8_t> bytes = encoded(m);
  bytes[6] = 0;  // minor version 0: the layout 1.0 wrote, chunk for chunk
  bytes[7] = 0;
  const std::string tone_tag = "TONE";
  REQUIRE(std::search(bytes.begin(), bytes.end(), tone_tag.begin(), tone_tag.end()) == bytes.end());
  Material back;
  REQUIRE(decode_material(bytes, "old.cbtf", back).ok());
  CHECK(back == m);
}

}  // namespace carbtf
