// A periodic height-field surface: what the sample-material renderer images, and the ground truth the
// analysis is measured against. The tile wraps around in both directions, so every rendered image is
// seamless too.
//
// Texel (col, row) has row 0 at the top. World axes: +x to the right (col), +y up (towards row 0), +z
// out of the surface; directions follow carbtf/analysis/btf/directions.hpp.
#pragma once

#include <cstdint>
#include <vector>

namespace carbtf {

struct Surface {
  std::uint32_t size = 0;     // the tile is size x size texels
  std::vector<float> height;  // size * size, in texel units (one unit = one texel's width)
  std::vector<float> albedo;  // size * size * 3, linear RGB diffuse reflectance in [0, 1]
  float specular = 0.04f;     // weight of the glossy lobe
  float gloss = 40.0f;        // its Blinn-Phong exponent
};

// Unit normals from central differences of the height, size * size * 3 (x, y, z).
std::vector<float> surface_normals(const Surface& surface);

}  // namespace carbtf
