// The UBO2003 layout inside a .zip (flat, per-view folders, or both under one enclosing folder).
#pragma once

#include "carbtf/analysis/btf/btf_reader.hpp"

namespace carbtf {

BtfDataset read_ubo2003_zip(const std::filesystem::path& archive, const BtfLoadOptions& options,
                            std::vector<std::string>& warnings);

}  // namespace carbtf
