// Records the mip levels of the textures the render pass samples (material/mip_levels.hpp says how many):
// a blit with a linear filter at a scale of exactly one half makes each texel the mean of 2 x 2. The
// owner of an image records them: the synthesizer, ResidentImages, TextureArray.
#pragma once

#include <cstdint>
#include <span>

#include "carbtf/engine/material/mip_levels.hpp"
#include "carbtf/engine/status.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

// Whether the device can make mip levels of `format` by linear blits (optimal tiling).
bool can_blit_mips(const Context& context, VkFormat format) noexcept;

// Where the first blit reads: one level of an image, readable by transfer (the caller's barrier
// made its writes available), in `layout` (TRANSFER_SRC_OPTIMAL; validation calls GENERAL slow), left so.
struct MipBlitSource {
  VkImage image = VK_NULL_HANDLE;
  std::uint32_t level = 0;
  VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  std::uint32_t width = 0;  // of that level
  std::uint32_t height = 0;
};

// Records the blits that fill `count` levels of `target` from `first_level` on, each half the size of
// the one before it, the first half the source's size, for each of `layers` (the same layer index in
// the source and the target). The target levels' old contents are discarded; they end in
// `final_layout`, visible to fragment and compute shader reads. out_of_host_memory, recording nothing, when
// the barrier lists cannot be built.
Status record_mip_blits(const Context& context, VkCommandBuffer command_buffer, const MipBlitSource& source,
                        VkImage target, std::uint32_t first_level, std::uint32_t count,
                        std::span<const std::uint32_t> layers, VkImageLayout final_layout) noexcept;

}  // namespace carbtf
