// The .cbtf material file: bit-exact round trip, clear errors, and 10,000 hostile mutations that must
// be rejected or read without a crash (this file also runs under ASan/UBSan, label "sanitize").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>

#include "carbtf/engine/material/car_stability.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/material/range_tiles.hpp"
#include "carbtf/reference/noise.hpp"
#include "carbtf/reference/synthetic_material.hpp"
#include "material_bytes.hpp"
#include "scratch_folder.hpp"
#include "test_range_tiles.hpp"

namespace carbtf {
namespace {

using test::fix_crcs;

// A valid material exercising every chunk: odd counts, negative and extreme floats, every neighbourhood
// shape.
Material sample_material() {
  Material m;
  for (int i = 0; i < 7; ++i)
    m.lights.push_back({0.2f * static_cast<float>(i), 0.9f * static_cast<float>(i)});
  for (int i = 0; i < 5; ++i)
    m.views.push_back({0.3f * static_cast<float>(i), -1.5f + static_cast<float>(i)});
  const auto candidates = neighbourhood_shapes();
  for (std::uint32_t s = 0; s < 3; ++s) {
    SubspaceModel sub;
    sub.light = s;
    sub.view = 4 - s;
    sub.width = 256;
    sub.height = 128 + s;
    sub.channels = 3;
    sub.levels = s + 1;
    sub.colour_mean = {0.1f, 0.2f, 1e-30f};
    sub.colour_transform = {1, 0, 0, 0, -1, 0, 0, 0, 0.99f * kMaxModelMagnitude};
    for (std::uint32_t b = 0; b < sub.levels * 3; ++b) {
      CarBandModel band;
      band.neighbourhood = candidates[(s * 3 + b) % candidates.size()];
      for (std::size_t k = 0; k < band.neighbourhood.size(); ++k)
        band.gamma.push_back(0.01f * static_cast<float>(k) - 0.03f);
      band.sigma = 0.5f + static_cast<float>(b);
      band.mean = -2.0f;
      band.band_std = 1.25f;
      band.flags = b % 2 ? car_band_repaired : 0u;
      sub.bands.push_back(band);
    }
    m.subspaces.push_back(sub);
  }
  for (std::size_t i = 0; i < m.lights.size() * m.views.size(); ++i)
    m.subspace_index.push_back(static_cast<std::uint8_t>(i % 3));
  const auto noise = [](std::uint32_t r, std::uint32_t c) {
    return double{
        reference::gaussian_noise(1, 0, static_cast<std::int32_t>(r), static_cast<std::int32_t>(c))};
  };
  m.range = test::windowed_range_tiles(
      noise, [&](std::uint32_t r, std::uint32_t c) { return std::abs(noise(r, c)) * 0.5 + 0.5; },
      {.map_rows = 24, .map_cols = 20, .tile_size = 8});
  m.settings = {{"source", "unit test"}, {"seed", "1"}, {"empty", ""}};
  return m;
}

std::vector<std::uint8_t> encoded(const Material& m) {
  std::vector<std::uint8_t> bytes;
  // Plain chunks: the tests below patch payload bytes in place.
  const Status s = encode_material(m, bytes, {.deflate = false});
  INFO(s.message());
  REQUIRE(s.ok());
  return bytes;
}

}  // namespace

TEST_CASE("a material survives encode and decode bit for bit", "[material_file]") {
  const Material original = sample_material();
  REQUIRE(validate_material(original).ok());
  const std::vector<std::uint8_t> bytes = encoded(original);
  Material decoded;
  const Status s = decode_material(bytes, "memory", decoded);
  INFO(s.message());
  REQUIRE(s.ok());
  REQUIRE(decoded == original);  // floats compared exactly, so bit-exact for all finite values
  REQUIRE(encoded(decoded) == bytes);

  SECTION("through a file, and the chunk breakdown adds up") {
    const auto folder = test::scratch_folder("material_file");
    const std::string path = (folder / "m.cbtf").string();
    REQUIRE(write_material_file(path, original).ok());
    Material from_file;
    REQUIRE(read_material_file(path, from_file).ok());
    REQUIRE(from_file == original);
    std::vector<MaterialChunkInfo> chunks;
    REQUIRE(list_material_chunks(bytes, chunks).ok());
    std::uint64_t total = 12;
    for (const auto& c : chunks) total += c.total_bytes;
    CHECK(total == bytes.size());
    std::vector<std::string> tags;
    for (const auto& c : chunks) tags.push_back(c.tag);
    CHECK(tags == std::vector<std::string>{"SETT", "DIRS", "INDX", "SUBS", "RNGE", "TONE"});
    // The file written is deflated; its listing names each inner chunk with its plain size.
    std::vector<std::uint8_t> on_disk;
    REQUIRE(read_material_file_bytes(path, on_disk).ok());
    REQUIRE(list_material_chunks(on_disk, chunks).ok());
    std::size_t deflated_chunks = 0;
    for (const auto& c : chunks) {
      CHECK(c.known);
      if (c.inflated_bytes > 0) {
        ++deflated_chunks;
        CHECK(c.total_bytes < c.inflated_bytes);
      }
    }
    CHECK(deflated_chunks >= 3);
    std::filesystem::remove_all(folder);
  }
}

TEST_CASE("material file errors name the file and the problem", "[material_file]") {
  const std::vector<std::uint8_t> good = encoded(sample_material());
  Material m;
  auto message = [&](std::vector<std::uint8_t> bytes) {
    const Status s = decode_material(bytes, "bad.cbtf", m);
    REQUIRE_FALSE(s.ok());
    CHECK(s.code() == ErrorCode::invalid_material);
    CHECK(s.message().rfind("bad.cbtf: ", 0) == 0);
    return s.message();
  };
  CHECK_THAT(message({}), Catch::Contains("too short"));
  CHECK_THAT(message({'P', 'K', 3, 4, 0, 0}), Catch::Contains("not a carbtf material file"));
  auto newer = good;
  newer[4] = 2;
  CHECK_THAT(message(newer),
             Catch::Contains("format 2." + std::to_string(kMaterialFormatMinor) + " is not supported"));
  CHECK_THAT(message(std::vector<std::uint8_t>(good.begin(), good.end() - 7)), Catch::Contains("truncated"));
  auto flipped = good;
  flipped[40] ^= 0x10;
  CHECK_THAT(message(flipped), Catch::Contains("CRC mismatch"));
  auto trailing = good;
  trailing.push_back(0);
  CHECK_THAT(message(trailing), Catch::Contains("unexpected bytes"));
  // An index entry naming a subspace that does not exist, with a valid CRC.
  Material bad_index = sample_material();
  auto bytes = encoded(bad_index);
  const std::string index_tag = "INDX";
  const auto at = std::search(bytes.begin(), bytes.end(), index_tag.begin(), index_tag.end()) - bytes.begin();
  bytes[static_cast<std::size_t>(at) + 8 + 8] = 200;
  fix_crcs(bytes);
  CHECK_THAT(message(bytes), Catch::Contains("names subspace 200 of 3"));

  Material from_file;
  const Status missing = read_material_file("/nonexistent/material.cbtf", from_file);
  CHECK(missing.code() == ErrorCode::file_error);
  CHECK_THAT(missing.message(), Catch::Contains("/nonexistent/material.cbtf"));
}

std::vector<std::uint8_t> deflated(const Material& m) {
  std::vector<std::uint8_t> bytes;
  REQUIRE(encode_material(m, bytes).ok());
  return bytes;
}

// An optional chunk `tag`: absent from `m` as given, which reads back with `is_default`; present once
// `set` fills it, and read back whole, plain and deflated. Returns the plain bytes of the set material
// and the offset of the chunk's first payload word, for the caller's hostile values.
std::pair<std::vector<std::uint8_t>, std::size_t> checked_optional_chunk(
    Material m, const std::string& tag, const std::function<void(Material&)>& set,
    const std::function<bool(const Material&)>& is_default) {
  const std::vector<std::uint8_t> without = encoded(m);
  CHECK(std::search(without.begin(), without.end(), tag.begin(), tag.end()) == without.end());
  Material back;
  REQUIRE(decode_material(without, "x.cbtf", back).ok());
  CHECK(is_default(back));
  set(m);
  for (const auto& bytes : {encoded(m), deflated(m)}) {
    REQUIRE(decode_material(bytes, "x.cbtf", back).ok());
    CHECK(back == m);
  }
  std::vector<std::uint8_t> bytes = encoded(m);
  const auto at = static_cast<std::size_t>(std::search(bytes.begin(), bytes.end(), tag.begin(), tag.end()) -
                                           bytes.begin());
  REQUIRE(at < bytes.size());
  return {std::move(bytes), at + 8};  // after the tag and the size
}

// Each of `hostile` written as the float at bytes[at] (CRCs fixed): the file is refused with a message
// naming it and holding every part of `expected`.
void check_refused_floats(std::vector<std::uint8_t>& bytes, std::size_t at,
                          std::initializer_list<float> hostile, std::initializer_list<std::string> expected) {
  Material back;
  for (const float value : hostile) {
    std::memcpy(&bytes[at], &value, 4);
    fix_crcs(bytes);
    const std::string message = decode_material(bytes, "bad.cbtf", back).message();
    CHECK_THAT(message, Catch::Contains("bad.cbtf"));
    for (const std::string& part : expected) CHECK_THAT(message, Catch::Contains(part));
  }
}

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

// A material whose relief is smooth at the scale of its 32-texel tiles, as measured reliefs are: the
// case the raster filter (format 1.3) is for.
Material smooth_relief_material() {
  Material m = sample_material();
  const auto height = [](std::uint32_t r, std::uint32_t c) {
    return 3.0 * std::sin(0.21 * static_cast<double>(r)) * std::cos(0.17 * static_cast<double>(c)) +
           0.05 * reference::gaussian_noise(2, 0, static_cast<std::int32_t>(r), static_cast<std::int32_t>(c));
  };
  m.range = test::windowed_range_tiles(
      height, [&](std::uint32_t r, std::uint32_t c) { return 1.0 + 0.1 * height(r, c); },
      {.map_rows = 80, .map_cols = 72, .tile_size = 32});
  return m;
}

// The byte offset of the DEFL chunk whose inner tag is `inner`, or npos.
std::size_t deflated_chunk_at(const std::vector<std::uint8_t>& bytes, const std::string& inner) {
  const std::string defl = "DEFL";
  for (auto it = bytes.begin(); (it = std::search(it, bytes.end(), defl.begin(), defl.end())) != bytes.end();
       ++it) {
    const auto at = static_cast<std::size_t>(it - bytes.begin());
    if (at + 12 <= bytes.size() &&
        std::equal(inner.begin(), inner.end(), bytes.begin() + static_cast<std::ptrdiff_t>(at + 8)))
      return at;
  }
  return std::string::npos;
}

// A relief rough at the texel scale, as measured leather is, cut into 32^2 patches of a 64 x 56 map,
// which overlap: what the window filter (format 1.5) is for.
Material rough_relief_material(bool fill_each_patch = false) {
  Material m = sample_material();
  const auto noise = [](std::uint32_t r, std::uint32_t c) {
    return double{
        reference::gaussian_noise(3, 0, static_cast<std::int32_t>(r), static_cast<std::int32_t>(c))};
  };
  m.range = test::windowed_range_tiles(
      noise, [&](std::uint32_t r, std::uint32_t c) { return 1.0 + 0.2 * std::abs(noise(r, c)); },
      {.map_rows = 64, .map_cols = 56, .tile_size = 32});
  if (fill_each_patch) fill_unseen_patch_texels(m.range);
  return m;
}

// The same relief with each patch filled on its own (format 1.3's filling), so its patches no longer
// agree where one shows a texel and another does not: the raster filter's case, not the window filter's.
Material patch_filled_material() {
  Material m = smooth_relief_material();
  fill_unseen_patch_texels(m.range);
  return m;
}

// Which patch texels some tile shows, found by changing each and looking, independent of the code.
std::vector<bool> shown_patch_texels(const RangeTiles& tiles) {
  const std::size_t tile_texels = std::size_t{tiles.tile_size} * tiles.tile_size;
  auto composed = [&](const RangeTiles& t) {
    std::vector<float> all(tile_texels * range_tile_count(t));
    for (std::uint32_t i = 0; i < range_tile_count(t); ++i)
      compose_range_tile(t, i, std::span<float>(all).subspan(i * tile_texels, tile_texels));
    return all;
  };
  std::vector<bool> shown(tiles.patches.size());
  const std::vector<float> heights = composed(tiles);
  for (std::size_t i = 0; i < tiles.patches.size(); ++i) {
    RangeTiles probe = tiles;
    probe.patches[i] = static_cast<std::uint16_t>(probe.patches[i] ^ 1u);
    shown[i] = composed(probe) != heights;
  }
  return shown;
}

// `m` deflated, after checking that it reads back equal.
std::vector<std::uint8_t> deflated_round_trip(const Material& m) {
  const std::vector<std::uint8_t> packed = deflated(m);
  Material back;
  REQUIRE(decode_material(packed, "x.cbtf", back).ok());
  CHECK(back == m);
  return packed;
}

// The message `packed` is refused with once its `width` bytes at `at` hold `value` (CRCs fixed).
std::string refused_with(std::vector<std::uint8_t> bytes, std::size_t at, std::uint32_t value, int width) {
  for (int i = 0; i < width; ++i)
    bytes[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(value >> (8 * i));
  fix_crcs(bytes);
  Material damaged;
  const Status s = decode_material(bytes, "bad.cbtf", damaged);
  REQUIRE_FALSE(s.ok());
  return s.message();
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

TEST_CASE("a relief tone outside its range or of the wrong size is refused", "[material_file][tone]") {
  const Material good = sample_material();
  auto message = [](const Material& m) {
    const Status s = validate_material(m);
    REQUIRE_FALSE(s.ok());
    return s.message();
  };
  Material negative = good;
  negative.range.tone_offset = -0.5f;
  CHECK_THAT(message(negative), Catch::Contains("relief tone") && Catch::Contains("leaves [0,"));
  Material huge = good;
  huge.range.tone.front() = 255;
  huge.range.tone_scale = 1.0f;  // 255 at the top, beyond kMaxRangeTone
  Material few_bits =
      good;  // a 5-bit tone: its scale may be large, as long as the values it reaches are in range
  for (std::uint8_t& t : few_bits.range.tone) t = static_cast<std::uint8_t>(t % 32);
  few_bits.range.tone_offset = 0.1f;
  few_bits.range.tone_scale = 0.12f;
  CHECK(validate_material(few_bits).ok());
  CHECK_THAT(message(huge), Catch::Contains("relief tone"));
  Material nan = good;
  nan.range.tone_scale = std::nanf("");
  CHECK_THAT(message(nan), Catch::Contains("not finite"));
  Material short_tone = good;
  short_tone.range.tone.pop_back();
  CHECK_THAT(message(short_tone), Catch::Contains("the relief tone has"));
  // One plane or three (R, G, B); two is neither.
  Material two_planes = good, three_planes = good;
  two_planes.range.tone.insert(two_planes.range.tone.end(), good.range.tone.begin(), good.range.tone.end());
  CHECK_THAT(message(two_planes),
             Catch::Contains("the relief tone has") && Catch::Contains("one plane or three"));
  for (int k = 0; k < 2; ++k)
    three_planes.range.tone.insert(three_planes.range.tone.end(), good.range.tone.begin(),
                                   good.range.tone.end());
  CHECK(validate_material(three_planes).ok());
}

TEST_CASE("a relief tone of three colour planes reads back, is filtered as rasters and filled plane by plane",
          "[material_file][tone][raster]") {
  Material m = smooth_relief_material();
  RangeTiles& r = m.range;
  const std::vector<std::uint8_t> grey = r.tone;
  const std::uint8_t top = *std::max_element(grey.begin(), grey.end());
  for (std::uint8_t q : grey) r.tone.push_back(static_cast<std::uint8_t>(top - q));
  for (std::uint8_t q : grey) r.tone.push_back(static_cast<std::uint8_t>(q / 2));
  REQUIRE(tone_planes(r) == 3);
  const std::size_t tile_texels = std::size_t{r.tile_size} * r.tile_size;
  auto composed = [&](const RangeTiles& t, RangeChannel channel) {
    std::vector<float> all(tile_texels * range_tile_count(t));
    for (std::uint32_t i = 0; i < range_tile_count(t); ++i)
      compose_range_tile(t, i, std::span<float>(all).subspan(i * tile_texels, tile_texels), channel);
    return all;
  };
  const std::vector<float> green = composed(r, RangeChannel::tone_green),
                           blue = composed(r, RangeChannel::tone_blue);
  CHECK(green != composed(r, RangeChannel::tone));
  CHECK(blue != green);
  // Filling what no tile shows changes no plane's tiles, and sets every plane's unseen texels from
  // that plane's shown ones alone: random values there are overwritten alike.
  fill_unseen_patch_texels(r);
  CHECK(composed(r, RangeChannel::tone_green) == green);
  CHECK(composed(r, RangeChannel::tone_blue) == blue);
  const std::vector<bool> shown = shown_patch_texels(r);
  RangeTiles scrambled = r;
  std::mt19937 rng(3);
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < shown.size(); ++i) {
      if (!shown[i]) scrambled.tone[k * shown.size() + i] = static_cast<std::uint8_t>(rng() % 256);
    }
  }
  REQUIRE(scrambled != r);
  fill_unseen_patch_texels(scrambled);
  CHECK(scrambled == r);
  const std::vector<std::uint8_t> packed = deflated_round_trip(m);
  const std::size_t tone_at = deflated_chunk_at(packed, "TONE");
  REQUIRE(tone_at != std::string::npos);
  REQUIRE(packed[tone_at + 16] >= 9);  // a raster filter, over every plane's patches
  std::uint32_t rasters = 0;
  for (int i = 0; i < 4; ++i)
    rasters |= std::uint32_t{packed[tone_at + 30 + static_cast<std::size_t>(i)]} << (8 * i);
  CHECK(rasters == 3 * 2 * r.edge_colours);
}

TEST_CASE("tone weights read back, are left out when all 1, and are refused out of range",
          "[material_file][tone]") {
  Material m = sample_material();
  const std::string twgt = "TWGT";
  SECTION("all 1: no TWGT chunk, as a format 1.1 file") {
    const std::vector<std::uint8_t> bytes = encoded(m);
    CHECK(std::search(bytes.begin(), bytes.end(), twgt.begin(), twgt.end()) == bytes.end());
    Material back;
    REQUIRE(decode_material(bytes, "x.cbtf", back).ok());
    for (const SubspaceModel& s : back.subspaces) CHECK(s.tone_weight == 1.0f);
  }
  SECTION("per subspace, plain and deflated") {
    m.subspaces[0].tone_weight = 0.0f;
    m.subspaces[2].tone_weight = 0.5f;
    for (const auto& bytes : {encoded(m), deflated(m)}) {
      Material back;
      REQUIRE(decode_material(bytes, "x.cbtf", back).ok());
      CHECK(back == m);
    }
    std::vector<std::uint8_t> bytes = encoded(m);
    const auto at = static_cast<std::size_t>(
        std::search(bytes.begin(), bytes.end(), twgt.begin(), twgt.end()) - bytes.begin());
    REQUIRE(at < bytes.size());
    SECTION("a weight beyond 1") {
      const float two = 2.0f;
      std::memcpy(&bytes[at + 8 + 4 + 4 * 2], &two, 4);  // tag, size, count, then subspace 2's weight
      fix_crcs(bytes);
      Material back;
      const Status s = decode_material(bytes, "bad.cbtf", back);
      CHECK_THAT(s.message(), Catch::Contains("bad.cbtf") &&
                                  Catch::Contains("subspace 2 has tone weight 2") &&
                                  Catch::Contains("outside 0..1"));
    }
    SECTION("a count that is not the subspaces'") {
      bytes[at + 8] = 2;  // 2 weights claimed, 3 stored: the chunk then has trailing bytes
      fix_crcs(bytes);
      Material back;
      CHECK_FALSE(decode_material(bytes, "bad.cbtf", back).ok());
    }
  }
  SECTION("validation names the subspace") {
    m.subspaces[1].tone_weight = std::nanf("");
    const Status s = validate_material(m);
    CHECK_THAT(s.message(), Catch::Contains("subspace 1 has tone weight"));
  }
}

TEST_CASE("a coloured tone reads back and is left out when grey and refused out of range",
          "[material_file][tone]") {
  Material m = sample_material();
  const std::string tchr = "TCHR";
  SECTION("grey: no TCHR chunk, and a file without one reads as grey") {
    const std::vector<std::uint8_t> bytes = encoded(m);
    CHECK(std::search(bytes.begin(), bytes.end(), tchr.begin(), tchr.end()) == bytes.end());
    Material back;
    REQUIRE(decode_material(bytes, "x.cbtf", back).ok());
    CHECK(back.range.tone_chroma == std::array<float, 3>{1.0f, 1.0f, 1.0f});
  }
  SECTION("coloured, plain and deflated") {
    m.range.tone_chroma = {1.3f, 1.2f, 0.6f};
    for (const auto& bytes : {encoded(m), deflated(m)}) {
      Material back;
      REQUIRE(decode_material(bytes, "x.cbtf", back).ok());
      CHECK(back == m);
    }
    std::vector<std::uint8_t> bytes = encoded(m);
    const auto at = static_cast<std::size_t>(
        std::search(bytes.begin(), bytes.end(), tchr.begin(), tchr.end()) - bytes.begin());
    REQUIRE(at < bytes.size());
    for (const float hostile : {5.0f, -4.5f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
      std::memcpy(&bytes[at + 8 + 4], &hostile, 4);  // tag, size, then the green slope
      fix_crcs(bytes);
      Material back;
      const Status s = decode_material(bytes, "bad.cbtf", back);
      CHECK_THAT(s.message(), Catch::Contains("bad.cbtf") && Catch::Contains("tone chroma 1 is") &&
                                  Catch::Contains("outside -4..4"));
    }
    bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at + 8 + 12), {0, 0, 0, 0});  // a fourth value
    bytes[at + 4] = 16;
    fix_crcs(bytes);
    Material back;
    CHECK_FALSE(decode_material(bytes, "bad.cbtf", back).ok());
  }
  SECTION("validation checks it also without range tiles") {
    m.range = RangeTiles{};
    m.range.tile_size = 0;
    m.range.tone_chroma = {1.0f, std::nanf(""), 1.0f};
    CHECK_THAT(validate_material(m).message(), Catch::Contains("tone chroma 1"));
  }
}

TEST_CASE("feathered cuts read back while a file without FTHR has hard cuts and a hostile feather is refused",
          "[material_file][range_tiles]") {
  auto [bytes, at] = checked_optional_chunk(
      sample_material(), "FTHR", [](Material& m) { m.range.feather = 2; },
      [](const Material& m) { return m.range.feather == 0; });
  Material back;
  for (const std::uint32_t hostile : {5u, 0xFFFFFFFFu}) {
    std::memcpy(&bytes[at], &hostile, 4);
    fix_crcs(bytes);
    const Status s = decode_material(bytes, "bad.cbtf", back);
    CHECK_THAT(s.message(),
               Catch::Contains("bad.cbtf") && Catch::Contains("feather " + std::to_string(hostile)));
  }
}

TEST_CASE("cast shadows read back while a file without SHDW has none and a hostile scale is refused",
          "[material_file][shadows]") {
  auto [bytes, at] = checked_optional_chunk(
      sample_material(), "SHDW", [](Material& m) { m.range.shadow_scale = 0.5f; },
      [](const Material& m) { return m.range.shadow_scale == 0.0f; });
  check_refused_floats(bytes, at, {-0.5f, 4.5f, std::nanf(""), std::numeric_limits<float>::infinity()},
                       {"shadow scale", "outside 0..4"});
  // Shadows are cast by range tiles: a material without them cannot have any.
  Material tileless = sample_material();
  tileless.range = RangeTiles{};
  tileless.range.shadow_scale = 0.5f;
  CHECK_THAT(validate_material(tileless).message(), Catch::Contains("tile size 0 but tile data present"));
}

TEST_CASE("a specular lobe reads back while a file without SPEC has none and hostile values are refused",
          "[material_file][specular]") {
  auto [bytes, at] = checked_optional_chunk(
      sample_material(), "SPEC",
      [](Material& m) {
        m.range.specular_strength = 0.08f;
        m.range.specular_gloss = 32.0f;
      },
      [](const Material& m) { return m.range.specular_strength == 0.0f; });
  check_refused_floats(bytes, at, {-0.5f, 17.0f, std::nanf(""), std::numeric_limits<float>::infinity()},
                       {"specular strength", "outside 0..16"});
  const float strength = 0.08f;
  std::memcpy(&bytes[at], &strength, 4);
  check_refused_floats(bytes, at + 4, {0.5f, 2000.0f, std::nanf(""), -std::numeric_limits<float>::infinity()},
                       {"specular gloss", "outside 1..1024"});
  // The lobe follows the range tiles' normals: a material without them cannot have one.
  Material tileless = sample_material();
  tileless.range = RangeTiles{};
  tileless.range.specular_strength = 0.08f;
  tileless.range.specular_gloss = 32.0f;
  CHECK_THAT(validate_material(tileless).message(), Catch::Contains("tile size 0 but tile data present"));
}

TEST_CASE("pair gains read back while a file without PGAN has none and a hostile table is refused",
          "[material_file][pair_gains]") {
  const auto with_gains = [](Material& m) {
    m.pair_gains.resize(3 * m.subspace_index.size());
    for (std::size_t i = 0; i < m.pair_gains.size(); ++i)
      m.pair_gains[i] = static_cast<std::uint8_t>(i * 37 % 256);
  };
  auto [bytes, at] = checked_optional_chunk(sample_material(), "PGAN", with_gains,
                                            [](const Material& m) { return m.pair_gains.empty(); });
  Material m = sample_material();
  with_gains(m);
  REQUIRE(m.lights.size() * m.views.size() > 2);
  // A code means 2^((q - 128) / 64): 1 at 128, twice at 192, half at 64; no gains, 1.
  m.pair_gains[0] = 128;
  m.pair_gains[m.subspace_index.size() + 1] = 192;
  m.pair_gains[2 * m.subspace_index.size() + 2] = 64;
  CHECK(pair_gain(m, 0, 0, 0) == 1.0f);
  CHECK(pair_gain(m, 0, 1, 1) == 2.0f);
  CHECK(pair_gain(m, 0, 2, 2) == 0.5f);
  CHECK(pair_gain(sample_material(), 0, 1, 1) == 1.0f);
  // The table's direction counts must be the material's.
  Material back;
  const std::uint32_t lights = static_cast<std::uint32_t>(m.lights.size());
  for (const std::uint32_t hostile : {lights + 1, 0xFFFFFFFFu}) {
    std::vector<std::uint8_t> lying = bytes;
    std::memcpy(&lying[at], &hostile, 4);
    fix_crcs(lying);
    const Status s = decode_material(lying, "bad.cbtf", back);
    INFO(s.message());
    CHECK_THAT(s.message(),
               Catch::Contains("bad.cbtf") && (Catch::Contains("PGAN") || Catch::Contains("pair gains")));
  }
  Material wrong = sample_material();
  wrong.pair_gains.assign(3 * wrong.subspace_index.size() - 1, 128);
  CHECK_THAT(validate_material(wrong).message(), Catch::Contains("pair gains are"));
  Material spectral = sample_material();
  with_gains(spectral);
  {
    // A valid four-channel (spectral) model: one more band per level, an identity transform.
    SubspaceModel& sub = spectral.subspaces[0];
    std::vector<CarBandModel> bands;
    for (std::uint32_t level = 0; level < sub.levels; ++level) {
      for (std::uint32_t c = 0; c < 4; ++c) bands.push_back(sub.bands[level * 3 + std::min(c, 2u)]);
    }
    sub.bands = bands;
    sub.channels = 4;
    sub.colour_mean.push_back(0.5f);
    sub.colour_transform.assign(16, 0.0f);
    for (int i = 0; i < 4; ++i) sub.colour_transform[static_cast<std::size_t>(i * 5)] = 1.0f;
    Material without = spectral;
    without.pair_gains.clear();
    REQUIRE(validate_material(without).ok());
  }
  CHECK_THAT(validate_material(spectral).message(), Catch::Contains("pair gains are RGB"));
}

TEST_CASE("10,000 random corruptions and truncations are rejected or read without a crash",
          "[material_file][fuzz][slow]") {
  const bool deflate = GENERATE(false, true);
  INFO("deflated chunks: " << deflate);
  const std::vector<std::uint8_t> good = deflate ? deflated(sample_material()) : encoded(sample_material());
  std::mt19937_64 rng(20261122);
  int rejected = 0, accepted = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    std::vector<std::uint8_t> bytes = good;
    const int kind = trial % 5;
    auto position = [&] { return static_cast<std::size_t>(rng() % bytes.size()); };
    if (kind == 0) {
      bytes.resize(static_cast<std::size_t>(rng() % good.size()));
    } else if (kind == 1 || kind == 2) {
      const int flips = 1 + static_cast<int>(rng() % 8);
      for (int f = 0; f < flips; ++f) bytes[position()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
      if (kind == 2) fix_crcs(bytes);
    } else if (kind == 3) {
      // A hostile count or size: an extreme u32 anywhere, CRCs made valid again.
      constexpr std::uint32_t extremes[] = {0u, 1u, 0x7FFFFFFFu, 0xFFFFFFFFu, 0x10000u, 4096u, 65u};
      const std::uint32_t value = extremes[rng() % 7];
      const std::size_t at = position() & ~std::size_t{3};
      for (int i = 0; i < 4 && at + i < bytes.size(); ++i)
        bytes[at + i] = static_cast<std::uint8_t>(value >> (8 * i));
      fix_crcs(bytes);
    } else {
      // Cut or duplicate a span in the middle, CRCs made valid again.
      const std::size_t a = position(), b = position();
      const std::size_t lo = std::min(a, b), hi = std::max(a, b);
      if (rng() % 2) {
        bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(lo),
                    bytes.begin() + static_cast<std::ptrdiff_t>(hi));
      } else {
        std::vector<std::uint8_t> span(bytes.begin() + static_cast<std::ptrdiff_t>(lo),
                                       bytes.begin() + static_cast<std::ptrdiff_t>(hi));
        bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(hi), span.begin(), span.end());
      }
      fix_crcs(bytes);
    }
    Material m;
    const Status s = decode_material(bytes, "fuzz", m);
    if (s.ok()) {
      ++accepted;
      // Whatever is accepted is a valid material that encodes again.
      REQUIRE(validate_material(m).ok());
      std::vector<std::uint8_t> again;
      REQUIRE(encode_material(m, again).ok());
    } else {
      ++rejected;
      REQUIRE(s.message().rfind("fuzz: ", 0) == 0);
    }
    // Truncations and corruptions the CRC still covers must never pass. The minor version (bytes 6-7)
    // is the one field a reader may ignore: newer minor versions stay readable.
    bool covered_change = bytes.size() != good.size();
    for (std::size_t i = 0; i < bytes.size() && !covered_change; ++i)
      covered_change = bytes[i] != good[i] && (i < 6 || i > 7);
    if (kind <= 1 && covered_change) {
      INFO("trial " << trial);
      REQUIRE_FALSE(s.ok());
    }
  }
  // The rest may decode (a flipped bit of a float can still be a valid parameter) but only valid.
  INFO("rejected " << rejected << ", accepted " << accepted);
  CHECK(rejected + accepted == 10000);
  CHECK(rejected >= 4000);
}

}  // namespace carbtf

namespace carbtf {

TEST_CASE("a material is valid only if it is safe to synthesize", "[material_file]") {
  const Material good = sample_material();
  REQUIRE(validate_material(good).ok());
  auto refused = [](const Material& m) {
    const Status s = validate_material(m);
    REQUIRE_FALSE(s.ok());
    CHECK(s.code() == ErrorCode::invalid_material);
    return s.message();
  };
  SECTION("a diverging CAR recursion names its subspace, level and band, and the rule") {
    Material m = good;
    m.subspaces[2].bands[4].gamma.assign(m.subspaces[2].bands[4].gamma.size(), 1.5f);
    CHECK_THAT(refused(m), Catch::Contains("subspace 2 level 1 band 1") && Catch::Contains("unstable"));
    // One gamma of 1.1 on the left neighbour alone: a within-row root at 1.1.
    Material one = good;
    CarBandModel& band = one.subspaces[0].bands[0];
    band.neighbourhood = {{0, -1}};
    band.gamma = {1.1f};
    CHECK_THAT(refused(one),
               Catch::Contains("subspace 0 level 0 band 0") && Catch::Contains("spectral radius 1.1"));
    // Inside the margin but past it: a root at 0.997 is refused, one at 0.99 (the analysis's own
    // limit) is kept.
    band.gamma = {0.997f};
    CHECK_THAT(refused(one), Catch::Contains("unstable"));
    band.gamma = {0.99f};
    CHECK(validate_material(one).ok());
  }
  SECTION("numbers beyond the documented range are refused") {
    for (int field = 0; field < 5; ++field) {
      Material m = good;
      SubspaceModel& s = m.subspaces[1];
      const float huge = 3.4e38f;
      if (field == 0) s.bands[0].sigma = huge;
      if (field == 1) s.bands[0].mean = huge;
      if (field == 2) s.colour_transform[4] = -huge;
      if (field == 3) s.colour_mean[0] = std::numeric_limits<float>::quiet_NaN();
      if (field == 4) m.range.height_scale = 1e3f;  // 65535 steps of 1e3 texels
      INFO("field " << field);
      CHECK_THAT(refused(m), Catch::Contains("beyond +-1000000"));
    }
  }
  SECTION("two equal directions are refused before any render needs them") {
    Material m = good;
    m.views[3] = m.views[1];
    CHECK_THAT(refused(m), Catch::Contains("view directions: directions 1 and 3 are the same"));
  }
  SECTION("a hostile file with valid CRCs is refused, naming the file") {
    Material marked = good;
    marked.subspaces[0].bands[1].gamma[0] = 0.0123f;  // a marker no other float of the file equals
    std::vector<std::uint8_t> bytes = encoded(marked);
    REQUIRE(test::replace_float(bytes, 0.0123f, 1.5f) == 1);
    test::fix_crcs(bytes);
    Material m;
    const Status s = decode_material(bytes, "hostile.cbtf", m);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.message(),
               Catch::StartsWith("hostile.cbtf: subspace 0 level 0 band 1 is an unstable recursion"));
  }
}

TEST_CASE("the Schur-Cohn stability test agrees with known roots", "[material_file]") {
  const std::vector<CarNeighbour> left{{0, -1}};
  CHECK(car_spectral_radius(left, {0.5}) == Approx(0.5).epsilon(1e-9));
  CHECK(car_spectral_radius(left, {-1.2}) == Approx(1.2).epsilon(1e-9));
  // Separable (1 - a z1)(1 - b z2): roots a and b.
  const std::vector<CarNeighbour> separable{{0, -1}, {-1, 0}, {-1, -1}};
  CHECK(car_spectral_radius(separable, {0.99, 0.7, -0.693}) == Approx(0.99).epsilon(1e-6));
  CHECK(car_spectral_radius(separable, {0.3, 0.8, -0.24}) == Approx(0.8).epsilon(1e-6));
  // Second-order within-row recursion z^2 - 1.6 z + 0.89: complex roots of modulus sqrt(0.89).
  const std::vector<CarNeighbour> two{{0, -1}, {0, -2}};
  CHECK(car_spectral_radius(two, {1.6, -0.89}) == Approx(std::sqrt(0.89)).epsilon(1e-9));
  CHECK(car_roots_within(two, {1.6, -0.89}, 0.95));
  CHECK_FALSE(car_roots_within(two, {1.6, -0.89}, 0.94));
  CHECK(car_spectral_radius(left, {std::numeric_limits<double>::quiet_NaN()}) ==
        std::numeric_limits<double>::infinity());
}

}  // namespace carbtf
