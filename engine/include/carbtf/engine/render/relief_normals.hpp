// The range map's normals as the render pass reads them (docs/design.md 4.6): per texel, the unit
// normal of the central differences of the heights one texel apart, N = normalize(-dx, -dy, 1), with
// dx = (h[x + 1] - h[x - 1]) / 2 and dy = (h[y - 1] - h[y + 1]) / 2 (texture up is towards row 0), the
// edge texels repeated or, for periodic textures, the addresses wrapped. Stored, not differenced per
// fragment: a fragment reads one filtered normal instead of four heights, and the mip levels hold the
// mean of the unit normals under each texel, whose dot product with the light is the mean of the
// finer facets' (Lambert is linear in N), so a distant relief keeps its shading's mean and contrast.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace carbtf {

// width * height heights (texel units, row-major) -> width * height * 3 floats (x, y, z per texel).
void relief_normals(std::span<const float> heights, std::uint32_t width, std::uint32_t height, bool wrap,
                    std::vector<float>& out);

// Sets each RGBA texel's a to the length of its rgb: the range texture's normal layer at every mip
// level, whose w the fragment stage blends as the normal's length (carbtf_relief()).
void store_normal_lengths(std::span<float> rgba);

}  // namespace carbtf
