// Internal: the engine's one way of recording a pipeline barrier. Every memory dependency and layout
// change the engine records goes through these, so the stages and access masks of a dependency are
// written once, next to each other, and a reader checks them in one place.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "carbtf/engine/vulkan/vulkan_functions.hpp"

namespace carbtf::detail {

// Levels [first_level, first_level + levels) of layers [first_layer, first_layer + layers).
struct ColourRange {
  std::uint32_t first_level = 0;
  std::uint32_t levels = 1;
  std::uint32_t first_layer = 0;
  std::uint32_t layers = 1;
};

// A stage mask and the accesses in it that a dependency is about.
struct StageAccess {
  VkPipelineStageFlags stages = 0;
  VkAccessFlags access = 0;
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

// A global memory dependency: `before`'s writes made visible to `after`'s accesses.
inline void memory_barrier(const VulkanFunctions& vk, VkCommandBuffer command_buffer, StageAccess before,
                           StageAccess after) {
  auto barrier = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  barrier.srcAccessMask = before.access;
  barrier.dstAccessMask = after.access;
  vk.vkCmdPipelineBarrier(command_buffer, before.stages, after.stages, 0, 1, &barrier, 0, nullptr, 0,
                          nullptr);
}

// A layout change of `range` of a colour image, with its execution and memory dependency.
inline void transition_colour(const VulkanFunctions& vk, VkCommandBuffer command_buffer, VkImage image,
                              ColourRange range, VkImageLayout from, VkImageLayout to, StageAccess before,
                              StageAccess after) {
  const VkImageMemoryBarrier barrier = colour_barrier(image, range, before.access, after.access, from, to);
  vk.vkCmdPipelineBarrier(command_buffer, before.stages, after.stages, 0, 0, nullptr, 0, nullptr, 1,
                          &barrier);
}

// Image barriers built by the caller (several layers or levels, each its own change), recorded as one.
inline void image_barriers(const VulkanFunctions& vk, VkCommandBuffer command_buffer,
                           VkPipelineStageFlags before, VkPipelineStageFlags after,
                           std::span<const VkImageMemoryBarrier> barriers) {
  vk.vkCmdPipelineBarrier(command_buffer, before, after, 0, 0, nullptr, 0, nullptr,
                          static_cast<std::uint32_t>(barriers.size()), barriers.data());
}

// Compute writes and reads made visible to the next compute dispatch.
inline void compute_to_compute(const VulkanFunctions& vk, VkCommandBuffer command_buffer) {
  constexpr StageAccess shaders{VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT};
  memory_barrier(vk, command_buffer, shaders, shaders);
}

}  // namespace carbtf::detail
