#include "cli/owned_folder.hpp"

#include <algorithm>
#include <system_error>

#include "cli/cli_support.hpp"

namespace carbtf::cli {

namespace fs = std::filesystem;

OwnedFolder::OwnedFolder(fs::path root) : root_(std::move(root)) {
  if (root_.empty()) throw CommandError("--out: the output folder is empty");
  std::error_code error;
  if (fs::exists(root_, error)) {
    if (!fs::is_directory(root_, error)) throw CommandError(root_.string() + ": exists and is not a folder");
    return;
  }
  for (fs::path p = fs::absolute(root_, error); !p.empty() && !fs::exists(p, error); p = p.parent_path()) {
    created_folders_.push_back(p);
    if (p == p.parent_path()) break;
  }
  if (!fs::create_directories(root_, error) && error) {
    created_folders_.clear();
    throw CommandError(root_.string() + ": cannot create the folder (" + error.message() + ")");
  }
}

OwnedFolder::~OwnedFolder() {
  if (keep_) return;
  try {
    remove_created();
  } catch (...) {
    // A destructor reports nothing; what could not be removed stays.
  }
}

fs::path OwnedFolder::claim(const std::string& name) {
  const fs::path path = root_ / name;
  std::error_code error;
  if (fs::exists(fs::symlink_status(path, error))) {
    throw CommandError(path.string() +
                       ": already exists; this command does not overwrite it. Remove it or choose "
                       "another --out");
  }
  claimed_.push_back(path);
  return path;
}

void OwnedFolder::release(const fs::path& claimed) {
  const auto found = std::find(claimed_.begin(), claimed_.end(), claimed);
  if (found == claimed_.end()) return;  // never claimed: not this command's to remove
  std::error_code error;
  fs::remove_all(claimed, error);
  claimed_.erase(found);
}

void OwnedFolder::remove_created() {
  while (!claimed_.empty()) release(claimed_.back());
  std::error_code error;
  for (const fs::path& folder : created_folders_) {
    if (!fs::is_empty(folder, error) || error) break;  // something else lives there now
    fs::remove(folder, error);
  }
  created_folders_.clear();
}

}  // namespace carbtf::cli
