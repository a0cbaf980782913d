// libFuzzer target: the photometric-stereo light file (light_directions.txt, read_photometric_stereo)
// beside three small images. Input errors (InputError) are the expected outcome.
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  carbtf::fuzz::write_input("light_directions.txt", data, size);
  std::vector<std::string> warnings;
  try {
    (void)carbtf::read_photometric_stereo(carbtf::fuzz::scratch(), {1, false}, warnings);
  } catch (const std::exception&) {
  }
  return 0;
}
