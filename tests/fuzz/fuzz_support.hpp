// Shared by the libFuzzer targets: a scratch folder per process for the readers that take paths, and
// the one small image the dataset readers can point at.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "carbtf/analysis/image_io.hpp"

namespace carbtf::fuzz {

inline const std::filesystem::path& scratch() {
  static const std::filesystem::path folder = [] {
    const auto path = std::filesystem::temp_directory_path() / ("carbtf_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(path);
    // An 8x8 grey image that manifests and light files may list.
    const std::vector<float> grey(8 * 8 * 3, 0.5f);
    for (const char* name : {"a.png", "b.png", "c.png"}) write_rgb_image(path / name, grey, 8, 8);
    return path;
  }();
  return folder;
}

inline std::filesystem::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = scratch() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace carbtf::fuzz
