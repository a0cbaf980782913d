// The .cbtf material file: bit-exact round trip, clear errors, and 10,000 hostile mutations that must
// be rejected or read without a crash (this file also runs under ASan/UBSan, label "sanitize").
#include <catch2/catch.hpp>

#include "material_file_samples.hpp"

namespace carbtf {

using namespace material_file_samples;

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
