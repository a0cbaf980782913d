// libFuzzer target: the .cbtf material reader (engine/material_file.hpp) on arbitrary bytes. Anything but
// a clean Status is a finding: a crash, a sanitizer report, a hang, or a material that decodes but fails
// validation. Each input is read twice: as it is, and with its chunk CRCs mended, because a mutation
// almost never keeps a CRC valid and the payload parsers behind the CRC check (the inflater, its
// filters, every chunk decoder) would otherwise see only the seed files.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "carbtf/engine/material/material_file.hpp"
#include "material_bytes.hpp"

namespace {

void read(std::span<const std::uint8_t> bytes) {
  carbtf::Material material;
  if (carbtf::decode_material(bytes, "fuzz.cbtf", material).ok()) {
    // What the reader accepts must be what validation accepts, and must encode again.
    if (!carbtf::validate_material(material).ok()) std::abort();
    std::vector<std::uint8_t> again;
    if (!carbtf::encode_material(material, again).ok()) std::abort();
  }
  std::vector<carbtf::MaterialChunkInfo> chunks;
  (void)carbtf::list_material_chunks(bytes, chunks);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  read(bytes);
  std::vector<std::uint8_t> mended(bytes.begin(), bytes.end());
  carbtf::test::fix_crcs(mended);
  if (!std::equal(mended.begin(), mended.end(), bytes.begin())) read(mended);
  return 0;
}
