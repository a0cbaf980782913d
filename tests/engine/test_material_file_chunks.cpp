// The material file's optional chunks (TONE, TWGT, TCHR, FTHR, SHDW, SPEC, PGAN, RCHL): each reads back, is
// left out when it holds its default, and is refused with hostile values.
#include <catch2/catch.hpp>

#include "material_file_samples.hpp"

namespace carbtf {

using namespace material_file_samples;

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

TEST_CASE(
    "the relief's chroma levels read back while a file without RCHL has the default and a hostile count "
    "is refused",
    "[material_file][relief_chroma]") {
  for (const std::uint32_t levels : {0u, 2u, kMaxReliefChromaLevels}) {
    auto [bytes, at] = checked_optional_chunk(
        sample_material(), "RCHL", [&](Material& m) { m.range.chroma_levels = levels; },
        [](const Material& m) { return m.range.chroma_levels == kDefaultReliefChromaLevels; });
    Material back;
    for (const std::uint32_t hostile : {kMaxReliefChromaLevels + 1, 0xFFFFFFFFu}) {
      std::memcpy(&bytes[at], &hostile, 4);
      fix_crcs(bytes);
      const Status s = decode_material(bytes, "bad.cbtf", back);
      CHECK_THAT(s.message(), Catch::Contains("bad.cbtf") &&
                                  Catch::Contains("chroma " + std::to_string(hostile) + " levels"));
    }
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

TEST_CASE(
    "a specular view power reads back while a file without SPVW has none and hostile values are "
    "refused",
    "[material_file][specular]") {
  const auto with_lobe = [](Material& m) {
    m.range.specular_strength = 0.08f;
    m.range.specular_gloss = 32.0f;
  };
  Material lobed = sample_material();
  with_lobe(lobed);
  auto [bytes, at] = checked_optional_chunk(
      lobed, "SPVW", [](Material& m) { m.range.specular_view_power = 0.5f; },
      [](const Material& m) { return m.range.specular_view_power == 0.0f; });
  check_refused_floats(bytes, at, {-0.5f, 2.5f, std::nanf(""), std::numeric_limits<float>::infinity()},
                       {"specular view power", "outside 0..2"});
  // The gain is 1 at the top view and without a power, (1 / z)^power above the floor and constant below it.
  CHECK(specular_view_gain(0.0f, 0.3f) == 1.0f);
  CHECK(specular_view_gain(0.5f, 1.0f) == 1.0f);
  CHECK(specular_view_gain(0.5f, 0.5f) == Approx(std::sqrt(2.0)));
  CHECK(specular_view_gain(1.0f, 0.1f) == Approx(1.0 / kSpecularViewFloor));
  Material tileless = sample_material();
  tileless.range = RangeTiles{};
  tileless.range.specular_view_power = 0.5f;
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

}  // namespace carbtf
