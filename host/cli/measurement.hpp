// The measured BTF a material was analysed from, loaded to compare the model with it.
#pragma once

#include <string>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/engine/material.hpp"

namespace carbtf::cli {

// Loads `path` (printing its load warnings) and checks that its light and view directions are the
// material's; else CommandError naming `option`, the path and both direction counts.
BtfDataset load_measurement_of(const Material& material, const std::string& path, const std::string& option);

}  // namespace carbtf::cli
