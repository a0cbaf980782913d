// The material files the repository keeps (tests/fuzz/corpus/material_file, formats 1.1 to 1.10) read
// as they did when they were written: each decodes to the material whose plain encoding has the size and
// CRC-32 (of the bytes after the signature and version) recorded here, taken with the reader of main 203b7cd,
// before the file format became a chunk table; the deflated encoding is recorded too, so the writer's bytes
// are pinned as well. A reader that drops, reorders or misreads a chunk changes the plain encoding and fails.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>

#include "carbtf/engine/material/material_file.hpp"

namespace carbtf {
namespace {

struct StoredMaterial {
  const char* file;
  std::size_t plain_bytes;  // the decoded material encoded without deflate
  std::uint32_t plain_crc;
  std::size_t deflated_bytes;  // and with it, as `analyze` writes today (the encoder's filters included)
  std::uint32_t deflated_crc;
};

constexpr StoredMaterial kStoredMaterials[] = {
    {"leather_16_format_1_1.cbtf", 13782, 0x5F10648F, 2983, 0x09012653},
    {"leather_16_format_1_2_tone_weights.cbtf", 18763, 0x6C5EEBD2, 6979, 0x4B43AD1F},
    {"leather_16_format_1_3_raster.cbtf", 18548, 0x867F2FF2, 6608, 0x2F22BE70},
    {"leather_16_format_1_4_coloured_tone.cbtf", 18572, 0x2818F3F8, 6632, 0x9CA04B54},
    {"leather_40_format_1_5_windows.cbtf", 21936, 0xDBCE1339, 8710, 0x54610191},
    {"leather_16.cbtf", 10111, 0xF7D8A137, 2089, 0x339AA5AB},
    {"fabric16_planes.cbtf", 21242, 0xD6012BEC, 5874, 0x63B6F605},
    {"coast16_shadows.cbtf", 18692, 0x4DF3E513, 5670, 0xE31D1B8A},
    {"coast16_specular.cbtf", 18712, 0x72F85BB6, 5690, 0x745C225E},
};

TEST_CASE("the material files the repository keeps read back as they were written",
          "[material_file][compatibility]") {
  for (const StoredMaterial& stored : kStoredMaterials) {
    const std::string path = std::string(CARBTF_MATERIAL_CORPUS) + "/" + stored.file;
    INFO(path);
    Material material;
    const Status read = read_material_file(path, material);
    REQUIRE(read.ok());
    std::vector<std::uint8_t> plain;
    REQUIRE(encode_material(material, plain, {.deflate = false}).ok());
    std::vector<std::uint8_t> deflated;
    REQUIRE(encode_material(material, deflated).ok());
    // The CRCs cover everything after the signature and version (8 bytes), so that a new minor version,
    // which only the header records, leaves them as they are; the header is checked on its own.
    const auto after_version = [](const std::vector<std::uint8_t>& bytes) {
      return crc32(std::span(bytes).subspan(8));
    };
    CHECK(plain.size() == stored.plain_bytes);
    CHECK(after_version(plain) == stored.plain_crc);
    CHECK(deflated.size() == stored.deflated_bytes);
    CHECK(after_version(deflated) == stored.deflated_crc);
    const std::uint8_t version[8] = {'C', 'B', 'T', 'F', kMaterialFormatMajor, 0, kMaterialFormatMinor, 0};
    CHECK(std::equal(version, version + 8, deflated.begin()));
  }
}

}  // namespace
}  // namespace carbtf
