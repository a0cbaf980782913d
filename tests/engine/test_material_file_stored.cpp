// The material files the repository keeps (tests/fuzz/corpus/material_file, formats 1.1 to 1.10) read
// as they did when they were written: each decodes to the material whose plain encoding has the size and
// CRC-32 recorded here, taken with the reader of main 203b7cd, before the file format became a chunk
// table; the deflated encoding is recorded too, so the writer's bytes are pinned as well. A reader that
// drops, reorders or misreads a chunk changes the plain encoding and fails.
#include <catch2/catch.hpp>

#include <cstdint>
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
    {"leather_16_format_1_1.cbtf", 13782, 0xEFE2998C, 2983, 0x71BE966D},
    {"leather_16_format_1_2_tone_weights.cbtf", 18763, 0x427A2C11, 6979, 0x50C4BD5B},
    {"leather_16_format_1_3_raster.cbtf", 18548, 0x6E7BEDAF, 6608, 0x4C1A2AEA},
    {"leather_16_format_1_4_coloured_tone.cbtf", 18572, 0x808026F3, 6632, 0x2FE23045},
    {"leather_40_format_1_5_windows.cbtf", 21936, 0x85B06BC0, 8710, 0x38236841},
    {"leather_16.cbtf", 10111, 0xC2B581C4, 2089, 0xAB5378FF},
    {"fabric16_planes.cbtf", 21242, 0xDACEFDF0, 5874, 0x0090FB20},
    {"coast16_shadows.cbtf", 18692, 0x05621DF2, 5670, 0x45508761},
    {"coast16_specular.cbtf", 18712, 0x6CD89230, 5690, 0x117C0BBB},
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
    CHECK(plain.size() == stored.plain_bytes);
    CHECK(crc32(plain) == stored.plain_crc);
    CHECK(deflated.size() == stored.deflated_bytes);
    CHECK(crc32(deflated) == stored.deflated_crc);
  }
}

}  // namespace
}  // namespace carbtf
