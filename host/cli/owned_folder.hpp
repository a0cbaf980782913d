// An output folder that a command writes scratch data and results into, and that removes, when asked,
// only what the command created there: never a file or folder that was there before (a user's --out
// pointing at their home folder loses nothing).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace carbtf::cli {

class OwnedFolder {
 public:
  // Creates `root` (and missing parents) unless it exists; throws CommandError when it is not a folder
  // or cannot be created.
  explicit OwnedFolder(std::filesystem::path root);
  // Removes whatever is still claimed unless keep() was called (errors are ignored there).
  ~OwnedFolder();
  OwnedFolder(const OwnedFolder&) = delete;
  OwnedFolder& operator=(const OwnedFolder&) = delete;

  const std::filesystem::path& root() const { return root_; }

  // root / name for the command to create as scratch. Throws CommandError naming it when something is
  // already there, so that nothing of the user's is overwritten or later removed.
  std::filesystem::path claim(const std::string& name);
  // Removes one claimed path (and what the command wrote inside it) now.
  void release(const std::filesystem::path& claimed);
  // Removes every claimed path still there, then the root folder if this created it and it is empty.
  void remove_created();
  // Keeps everything: the destructor removes nothing.
  void keep() { keep_ = true; }

 private:
  std::filesystem::path root_;
  std::vector<std::filesystem::path> created_folders_;  // root and the parents this created, deepest first
  std::vector<std::filesystem::path> claimed_;
  bool keep_ = false;
};

}  // namespace carbtf::cli
