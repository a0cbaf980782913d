// An empty scratch folder under the system temp folder, unique to this process, so that test runs
// in parallel (ctest -j, two checkouts) never share one. Every folder made here is removed when the
// process exits, so that a test that stops half-way, or one whose files outlive its function (a
// helper that returns a path), leaves nothing under the temp folder.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace carbtf::test {

namespace detail {

class ScratchFolders {
 public:
  ScratchFolders() = default;
  ScratchFolders(const ScratchFolders&) = delete;
  ScratchFolders& operator=(const ScratchFolders&) = delete;
  ~ScratchFolders() {
    for (const std::filesystem::path& folder : folders_) {
      std::error_code ignored;
      std::filesystem::remove_all(folder, ignored);
    }
  }
  void add(const std::filesystem::path& folder) {
    const std::lock_guard lock(mutex_);
    for (const std::filesystem::path& known : folders_) {
      if (known == folder) return;
    }
    folders_.push_back(folder);
  }

 private:
  std::mutex mutex_;
  std::vector<std::filesystem::path> folders_;
};

inline ScratchFolders& scratch_folders() {
  static ScratchFolders folders;
  return folders;
}

}  // namespace detail

inline std::filesystem::path scratch_folder(const std::string& name) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("carbtf_test_" + std::to_string(getpid()) + "_" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  detail::scratch_folders().add(folder);
  return folder;
}

}  // namespace carbtf::test
