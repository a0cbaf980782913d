// How many mip levels a texture the render pass samples has (docs/design.md 4.6): each level halves
// the one above exactly, a texel being the mean of its 2 x 2 texels, for as long as both sides stay
// even, so no level resamples. The GPU makes them by blits (vulkan/mip_chain.hpp); the host, for the
// range texture and the CPU twin (analysis/reference/src/render_reference.cpp), as the same means
// (next_mip_level()).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace carbtf {

inline constexpr std::uint32_t kMaxMipLevels = 16;

// Level 0 included: 1 + the number of times both sides halve evenly, at most kMaxMipLevels. 1024^2
// has 11 levels, 96 x 80 has 5 (down to 6 x 5).
constexpr std::uint32_t mip_level_count(std::uint32_t width, std::uint32_t height) noexcept {
  std::uint32_t levels = 1;
  while (levels < kMaxMipLevels && width >= 2 && height >= 2 && width % 2 == 0 && height % 2 == 0) {
    width /= 2;
    height /= 2;
    ++levels;
  }
  return levels;
}

// The level above `level` (width x height texels of `channels` floats, row-major, both sides even) made
// on the host as a linear blit at half size makes it: each texel the half-way blend of the half-way
// blends of its 2 x 2 rows. For textures whose levels the host makes (TextureArray's host levels) and
// for the CPU twin.
std::vector<float> next_mip_level(std::span<const float> level, std::uint32_t width, std::uint32_t height,
                                  std::uint32_t channels);

}  // namespace carbtf
