// Internal: the image memory barrier every recorded layout change of a colour image takes.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

namespace carbtf::detail {

// Levels [first_level, first_level + levels) of layers [first_layer, first_layer + layers).
struct ColourRange {
  std::uint32_t first_level = 0;
  std::uint32_t levels = 1;
  std::uint32_t first_layer = 0;
  std::uint32_t layers = 1;
};

inline VkImageMemoryBarrier colour_barrier(VkImage image, ColourRange range, VkAccessFlags from,
                                           VkAccessFlags to, VkImageLayout old_layout,
                                           VkImageLayout new_layout) {
  VkImageMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  barrier.srcAccessMask = from;
  barrier.dstAccessMask = to;
  barrier.oldLayout = old_layout;
  barrier.newLayout = new_layout;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, range.first_level, range.levels, range.first_layer,
                              range.layers};
  return barrier;
}

}  // namespace carbtf::detail
