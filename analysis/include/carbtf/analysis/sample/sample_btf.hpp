// A sample surface rendered as a UBO2003 BTF on disk: the 81 x 81 images of `carbtf sample`, and the
// measured data the demo and `bench frame` start from.
#pragma once

#include <filesystem>
#include <string>

#include "carbtf/analysis/sample/surface.hpp"

namespace carbtf {

// `output` is a folder, or with `zip` the archive to create; `extension` is ".jpg", ".png" or ".exr".
void write_sample_btf(const Surface& surface, const std::filesystem::path& output,
                      const std::string& extension, bool zip);

}  // namespace carbtf
