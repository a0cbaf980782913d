// libFuzzer target: the UBO2014 .btf reader (analysis/btf/btf_reader.hpp, read_ubo2014_btf) on an
// arbitrary file, then every image of what it read (a DFMF file's are decoded on access). Input errors
// (InputError) are the expected outcome.
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = carbtf::fuzz::write_input("input.btf", data, size);
  std::vector<std::string> warnings;
  try {
    const carbtf::BtfDataset dataset = carbtf::read_ubo2014_btf(path, {1, false}, warnings);
    std::vector<float> rgb(dataset.pixel_count() * 3);
    for (const carbtf::LightView pair : dataset.present_pairs()) dataset.linear_rgb(pair, rgb);
  } catch (const std::exception&) {
  }
  return 0;
}
