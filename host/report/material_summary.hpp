// `carbtf info material.cbtf`: the model in a few lines (subspaces, bands, range tiles, tone, shadows,
// highlights, pair gains) and the file's size per chunk.
#pragma once

#include <string>

namespace carbtf::cli {

// Prints the summary on stdout; CommandError when the file cannot be read.
void print_material_summary(const std::string& path);

}  // namespace carbtf::cli
