// The materials and byte-level helpers the material-file tests share (test_material_file*.cpp): a material
// exercising every chunk, reliefs the raster and window filters are for, and encodings the tests patch.
#pragma once

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

namespace carbtf::material_file_samples {

using test::fix_crcs;

// A valid material exercising every chunk: odd counts, negative and extreme floats, every neighbourhood
// shape.
inline Material sample_material() {
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

inline std::vector<std::uint8_t> encoded(const Material& m) {
  std::vector<std::uint8_t> bytes;
  // Plain chunks: the tests below patch payload bytes in place.
  const Status s = encode_material(m, bytes, {.deflate = false});
  INFO(s.message());
  REQUIRE(s.ok());
  return bytes;
}

inline std::vector<std::uint8_t> deflated(const Material& m) {
  std::vector<std::uint8_t> bytes;
  REQUIRE(encode_material(m, bytes).ok());
  return bytes;
}

// An optional chunk `tag`: absent from `m` as given, which reads back with `is_default`; present once
// `set` fills it, and read back whole, plain and deflated. Returns the plain bytes of the set material
// and the offset of the chunk's first payload word, for the caller's hostile values.
inline std::pair<std::vector<std::uint8_t>, std::size_t> checked_optional_chunk(
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
inline void check_refused_floats(std::vector<std::uint8_t>& bytes, std::size_t at,
                                 std::initializer_list<float> hostile,
                                 std::initializer_list<std::string> expected) {
  Material back;
  for (const float value : hostile) {
    std::memcpy(&bytes[at], &value, 4);
    fix_crcs(bytes);
    const std::string message = decode_material(bytes, "bad.cbtf", back).message();
    CHECK_THAT(message, Catch::Contains("bad.cbtf"));
    for (const std::string& part : expected) CHECK_THAT(message, Catch::Contains(part));
  }
}

// A material whose relief is smooth at the scale of its 32-texel tiles, as measured reliefs are: the
// case the raster filter (format 1.3) is for.
inline Material smooth_relief_material() {
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
inline std::size_t deflated_chunk_at(const std::vector<std::uint8_t>& bytes, const std::string& inner) {
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
inline Material rough_relief_material(bool fill_each_patch = false) {
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
inline Material patch_filled_material() {
  Material m = smooth_relief_material();
  fill_unseen_patch_texels(m.range);
  return m;
}

// Which patch texels some tile shows, found by changing each and looking, independent of the code.
inline std::vector<bool> shown_patch_texels(const RangeTiles& tiles) {
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
inline std::vector<std::uint8_t> deflated_round_trip(const Material& m) {
  const std::vector<std::uint8_t> packed = deflated(m);
  Material back;
  REQUIRE(decode_material(packed, "x.cbtf", back).ok());
  CHECK(back == m);
  return packed;
}

// The message `packed` is refused with once its `width` bytes at `at` hold `value` (CRCs fixed).
inline std::string refused_with(std::vector<std::uint8_t> bytes, std::size_t at, std::uint32_t value,
                                int width) {
  for (int i = 0; i < width; ++i)
    bytes[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(value >> (8 * i));
  fix_crcs(bytes);
  Material damaged;
  const Status s = decode_material(bytes, "bad.cbtf", damaged);
  REQUIRE_FALSE(s.ok());
  return s.message();
}

}  // namespace carbtf::material_file_samples
