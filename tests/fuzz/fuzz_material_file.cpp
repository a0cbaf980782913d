// libFuzzer target: the .cbtf material reader (engine/material_file.hpp) on arbitrary bytes. Anything but
// a clean Status is a finding: a crash, a sanitizer report, a hang, or a material that decodes but fails
// validation.
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "carbtf/engine/material_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  carbtf::Material material;
  if (carbtf::decode_material(bytes, "fuzz.cbtf", material).ok()) {
    // What the reader accepts must be what validation accepts, and must encode again.
    if (!carbtf::validate_material(material).ok()) std::abort();
    std::vector<std::uint8_t> again;
    if (!carbtf::encode_material(material, again).ok()) std::abort();
  }
  std::vector<carbtf::MaterialChunkInfo> chunks;
  (void)carbtf::list_material_chunks(bytes, chunks);
  return 0;
}
