// libFuzzer target: the manifest reader (analysis/btf/btf_reader.hpp, read_manifest) on an arbitrary
// manifest.csv beside three small images. Input errors (InputError) are the expected outcome.
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = carbtf::fuzz::write_input("manifest.csv", data, size);
  std::vector<std::string> warnings;
  try {
    (void)carbtf::read_manifest(path, {1, false}, warnings);
  } catch (const std::exception&) {
  }
  return 0;
}
