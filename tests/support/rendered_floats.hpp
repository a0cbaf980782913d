// A rendered RGBA32F frame as floats, for the render tests.
#pragma once

#include <cstring>
#include <vector>

#include "carbtf/engine/render/mesh_renderer.hpp"

namespace carbtf::test {

inline std::vector<float> as_floats(const RenderedImage& image) {
  std::vector<float> out(image.bytes.size() / 4);
  std::memcpy(out.data(), image.bytes.data(), image.bytes.size());
  return out;
}

}  // namespace carbtf::test
