// libFuzzer target: the UBO2003 file and folder name parsers (analysis/btf/ubo2003_names.hpp).
#include <cstdint>
#include <string_view>

#include "carbtf/analysis/btf/ubo2003_names.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // The parser checks syntax only (the reader checks the index against the directions), so a crash or a
  // sanitizer report is the finding here.
  (void)carbtf::parse_ubo2003_name(text);
  int theta = 0, phi = 0;
  (void)carbtf::parse_ubo2003_view_folder(text, theta, phi);
  return 0;
}
