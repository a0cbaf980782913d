// Built-in sample materials: recipes (assets/materials/NAME.json) turned into periodic surfaces with
// known ground truth. Deterministic for a seed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "carbtf/analysis/sample/surface.hpp"

namespace carbtf {

// The assets folder: $CARBTF_ASSETS if set, else the source tree's assets/ (build tree), else the
// installed share/carbtf/assets.
std::filesystem::path asset_directory();

// Names of the recipes in asset_directory()/materials, sorted.
std::vector<std::string> sample_material_names();

// Builds the surface of recipe `name` (a built-in name, or a path to a recipe .json) at size x size.
// Throws InputError for an unknown name, a malformed recipe or unreadable source images.
Surface make_sample_surface(const std::string& name, std::uint32_t size, std::uint64_t seed);

}  // namespace carbtf
