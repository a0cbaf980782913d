#include "carbtf/engine/vulkan/mip_chain.hpp"

#include <new>
#include <vector>

#include "vulkan/barriers.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {

namespace {

VkImageMemoryBarrier level_barrier(VkImage image, std::uint32_t level, std::uint32_t layer,
                                   VkAccessFlags from, VkAccessFlags to, VkImageLayout old_layout,
                                   VkImageLayout new_layout) {
  return detail::colour_barrier(image, {level, 1, layer, 1}, from, to, old_layout, new_layout);
}

}  // namespace

bool can_blit_mips(const Context& context, VkFormat format) noexcept {
  VkFormatProperties properties{};
  context.vk().vkGetPhysicalDeviceFormatProperties(context.physical_device(), format, &properties);
  constexpr VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                          VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  return (properties.optimalTilingFeatures & needed) == needed;
}

Status record_mip_blits(const Context& context, VkCommandBuffer command_buffer, const MipBlitSource& source,
                        VkImage target, std::uint32_t first_level, std::uint32_t count,
                        std::span<const std::uint32_t> layers, VkImageLayout final_layout) noexcept {
  if (count == 0 || layers.empty()) return {};
  const VulkanFunctions& vk = context.vk();
  constexpr auto written = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, read = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  constexpr VkPipelineStageFlags shaders =
      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  try {
    std::vector<VkImageMemoryBarrier> barriers, last;
    std::vector<VkImageBlit> blits;
    barriers.reserve(layers.size() * count);
    last.reserve(layers.size() * count);
    blits.reserve(layers.size());
    for (std::uint32_t layer : layers) {
      for (std::uint32_t l = 0; l < count; ++l) {
        // Every level but the last was read by the next blit.
        last.push_back(level_barrier(target, first_level + l, layer, VK_ACCESS_TRANSFER_WRITE_BIT,
                                     VK_ACCESS_SHADER_READ_BIT, l + 1 < count ? read : written,
                                     final_layout));
      }
    }
    // Earlier draws may still read the target levels: an execution dependency orders the blits after.
    for (std::uint32_t layer : layers) {
      for (std::uint32_t l = 0; l < count; ++l) {
        barriers.push_back(level_barrier(target, first_level + l, layer, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                                         VK_IMAGE_LAYOUT_UNDEFINED, written));
      }
    }
    detail::image_barriers(vk, command_buffer, shaders | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, barriers);
    VkImage from = source.image;
    std::uint32_t from_level = source.level, width = source.width, height = source.height;
    VkImageLayout from_layout = source.layout;
    for (std::uint32_t l = 0; l < count; ++l) {
      const std::uint32_t to_level = first_level + l;
      blits.clear();
      for (std::uint32_t layer : layers) {
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, from_level, layer, 1};
        blit.srcOffsets[1] = {static_cast<std::int32_t>(width), static_cast<std::int32_t>(height), 1};
        blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, to_level, layer, 1};
        blit.dstOffsets[1] = {static_cast<std::int32_t>(width / 2), static_cast<std::int32_t>(height / 2), 1};
        blits.push_back(blit);
      }
      vk.vkCmdBlitImage(command_buffer, from, from_layout, target, written,
                        static_cast<std::uint32_t>(blits.size()), blits.data(), VK_FILTER_LINEAR);
      if (l + 1 == count) break;
      // The level just written is the next blit's source.
      barriers.clear();
      for (std::uint32_t layer : layers) {
        barriers.push_back(level_barrier(target, to_level, layer, VK_ACCESS_TRANSFER_WRITE_BIT,
                                         VK_ACCESS_TRANSFER_READ_BIT, written, read));
      }
      detail::image_barriers(vk, command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, barriers);
      from = target;
      from_level = to_level;
      from_layout = read;
      width /= 2;
      height /= 2;
    }
    detail::image_barriers(vk, command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT, shaders, last);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory recording mip levels"};
  }
}

}  // namespace carbtf
