// Loading measured BTFs. Every reader checks its input and throws InputError naming the file and the
// problem; none writes anything.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"

namespace carbtf {

struct BtfLoadOptions {
  unsigned threads = 0;   // decoding threads; 0: all hardware threads
  bool progress = true;   // progress bar on stderr when it is a terminal
};

// Loads whatever `path` is:
//   - a folder in the UBO2003 layout (flat, or per-view folders tvTTT_pvPPP), or a .zip of one;
// Missing (light, view) pairs are allowed: each becomes a line in `warnings`.
BtfDataset load_btf(const std::filesystem::path& path, const BtfLoadOptions& options,
                    std::vector<std::string>& warnings);

// The UBO2003 folder reader on its own.
BtfDataset read_ubo2003_folder(const std::filesystem::path& folder, const BtfLoadOptions& options,
                               std::vector<std::string>& warnings);

}  // namespace carbtf
