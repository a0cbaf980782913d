// Internal: the checks every UBO2003-named entry passes, wherever it is stored (folder or zip).
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "carbtf/analysis/btf/btf_dataset.hpp"

namespace carbtf::detail {

// Checks one UBO2003-named entry and returns its (light, view) pair. `folder_name` is the per-view
// folder it sits in, or empty for a flat layout. `seen` maps pair indices to the entries that had
// them, to report duplicates. Throws InputError naming `display_name`.
LightView ubo2003_pair(const std::string& display_name, const std::string& file_name,
                       const std::string& folder_name, std::map<std::uint32_t, std::string>& seen);

}  // namespace carbtf::detail
