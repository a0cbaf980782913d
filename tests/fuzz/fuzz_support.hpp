// Shared by the libFuzzer targets: a scratch folder per process for the readers that take paths, and
// the one small image the dataset readers can point at.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "carbtf/analysis/image_io.hpp"

namespace carbtf::fuzz {

// Removed when the fuzzer exits (libFuzzer ends with exit(), which runs static destructors), so a run
// leaves nothing in the temporary folder; a crash keeps it, beside the artifact that shows the input.
class ScratchFolder {
 public:
  ScratchFolder()
      : path_(std::filesystem::temp_directory_path() / ("carbtf_fuzz_" + std::to_string(getpid()))) {
    std::filesystem::create_directories(path_);
    // An 8x8 grey image that manifests and light files may list.
    const std::vector<float> grey(8 * 8 * 3, 0.5f);
    for (const char* name : {"a.png", "b.png", "c.png"}) write_rgb_image(path_ / name, grey, 8, 8);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline const std::filesystem::path& scratch() {
  static const ScratchFolder folder;
  return folder.path();
}

inline std::filesystem::path write_input(const std::string& name, const std::uint8_t* data,
                                         std::size_t size) {
  const std::filesystem::path path = scratch() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace carbtf::fuzz
