// An empty scratch folder under the system temp folder, unique to this process, so that test runs
// in parallel (ctest -j, two checkouts) never share one.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace carbtf::test {

inline std::filesystem::path scratch_folder(const std::string& name) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("carbtf_test_" + std::to_string(getpid()) + "_" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace carbtf::test
