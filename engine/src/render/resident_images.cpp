#include "carbtf/engine/render/resident_images.hpp"

#include <algorithm>
#include <limits>
#include <new>
#include <string>

#include "carbtf/engine/vulkan/mip_chain.hpp"
#include "vulkan/barriers.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {

namespace {

VkImageMemoryBarrier layout_change(VkImage image, std::uint32_t first, std::uint32_t count,
                                   VkAccessFlags from, VkAccessFlags to, VkImageLayout old_layout,
                                   VkImageLayout new_layout, std::uint32_t levels = 1) {
  return detail::colour_barrier(image, {0, levels, first, count}, from, to, old_layout, new_layout);
}

}  // namespace

Status ResidentImages::create(Context& context, const Material& material, std::uint32_t size,
                              std::uint32_t periodic_overlap, std::unique_ptr<ResidentImages>& out,
                              std::uint32_t mip_levels) noexcept {
  try {
    if (size == 0) return {ErrorCode::invalid_argument, "resident subspace images need a size above 0"};
    if (material.subspaces.empty())
      return {ErrorCode::invalid_argument, "the material has no subspace images to make resident"};
    std::unique_ptr<ResidentImages> images(new ResidentImages());
    images->context_ = &context;
    images->subspaces_ = static_cast<std::uint32_t>(material.subspaces.size());
    images->periodic_overlap_ = periodic_overlap;
    ImageCreateInfo info;
    info.width = info.height = size;
    info.array_layers = images->subspaces_;
    info.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    const std::uint32_t possible = can_blit_mips(context, info.format) ? mip_level_count(size, size) : 1;
    info.mip_levels = mip_levels == 0 ? possible : std::min(mip_levels, possible);
    // TRANSFER_SRC: level 0 is the source of the blits that make the mip levels.
    info.usage =
        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    info.debug_name = "carbtf resident subspace images";
    CARBTF_TRY(Image::create(context, info, images->image_));
    out = std::move(images);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory for the resident subspace images"};
  }
}

void ResidentImages::record_transition(VkCommandBuffer command_buffer) const noexcept {
  detail::transition_colour(context_->vk(), command_buffer, image_.handle(),
                            {0, VK_REMAINING_MIP_LEVELS, 0, subspaces_}, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_GENERAL, {VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0},
                            {VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT});
}

std::vector<std::uint32_t> ResidentImages::missing(std::span<const std::uint32_t> needed) const {
  std::vector<std::uint32_t> out;
  for (std::uint32_t s : needed) {
    if (s < subspaces_ && !resident_.contains(s)) out.push_back(s);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Status ResidentImages::record_add(VkCommandBuffer command_buffer, const SubspaceSynthesizer& synthesizer,
                                  std::span<const std::uint32_t> added) noexcept {
  try {
    if (synthesizer.width() != image_.info().width || synthesizer.height() != image_.info().height) {
      return {ErrorCode::invalid_argument,
              "the synthesis is " + std::to_string(synthesizer.width()) + "x" +
                  std::to_string(synthesizer.height()) + ", the resident images " +
                  std::to_string(image_.info().width) + "x" + std::to_string(image_.info().height)};
    }
    // The synthesis's layers go to TRANSFER_SRC and ours to TRANSFER_DST for the copy, then both back to
    // GENERAL: ours for the fragment stage, the synthesizer's as its record() leaves them.
    constexpr auto general = VK_IMAGE_LAYOUT_GENERAL;
    constexpr auto source = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   target = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    const bool mipped = image_.info().mip_levels > 1;
    std::vector<VkImageCopy> copies;
    std::vector<VkImageMemoryBarrier> before{layout_change(synthesizer.image(), 0, VK_REMAINING_ARRAY_LAYERS,
                                                           VK_ACCESS_SHADER_WRITE_BIT,
                                                           VK_ACCESS_TRANSFER_READ_BIT, general, source)};
    std::vector<VkImageMemoryBarrier> after{
        layout_change(synthesizer.image(), 0, VK_REMAINING_ARRAY_LAYERS, VK_ACCESS_TRANSFER_READ_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT, source, general)};
    for (std::uint32_t s : added) {
      if (s >= subspaces_ || synthesizer.layer_of(s) == std::numeric_limits<std::uint32_t>::max())
        return {ErrorCode::invalid_argument, "subspace image " + std::to_string(s) + " was not synthesized"};
      VkImageCopy copy{};
      copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, synthesizer.layer_of(s), 1};
      copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, s, 1};
      copy.extent = {synthesizer.width(), synthesizer.height(), 1};
      copies.push_back(copy);
      // Earlier draws read our layer: an execution dependency orders the copy after them.
      before.push_back(
          layout_change(image_.handle(), s, 1, 0, VK_ACCESS_TRANSFER_WRITE_BIT, general, target));
      // With mip levels, level 0 is next read by the blits that make them.
      after.push_back(mipped ? layout_change(image_.handle(), s, 1, VK_ACCESS_TRANSFER_WRITE_BIT,
                                             VK_ACCESS_TRANSFER_READ_BIT, target, source)
                             : layout_change(image_.handle(), s, 1, VK_ACCESS_TRANSFER_WRITE_BIT,
                                             VK_ACCESS_SHADER_READ_BIT, target, general));
    }
    if (copies.empty()) return {};
    const VulkanFunctions& vk = context_->vk();
    constexpr VkPipelineStageFlags shaders =
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    detail::image_barriers(vk, command_buffer, shaders, VK_PIPELINE_STAGE_TRANSFER_BIT, before);
    vk.vkCmdCopyImage(command_buffer, synthesizer.image(), source, image_.handle(), target,
                      static_cast<std::uint32_t>(copies.size()), copies.data());
    detail::image_barriers(vk, command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           shaders | VK_PIPELINE_STAGE_TRANSFER_BIT, after);
    if (mipped) {
      CARBTF_TRY(record_mip_blits(*context_, command_buffer,
                                  {image_.handle(), 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   image_.info().width, image_.info().height},
                                  image_.handle(), 1, image_.info().mip_levels - 1, added, general));
      std::vector<VkImageMemoryBarrier> back;
      for (std::uint32_t s : added) {
        back.push_back(layout_change(image_.handle(), s, 1, VK_ACCESS_TRANSFER_READ_BIT,
                                     VK_ACCESS_SHADER_READ_BIT, source, general));
      }
      detail::image_barriers(vk, command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT, shaders, back);
    }
    resident_.insert(added.begin(), added.end());
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory recording the resident images' copy"};
  }
}

MaterialTextures ResidentImages::textures() const {
  MaterialTextures textures;
  textures.view = image_.view();
  textures.mip_levels = image_.info().mip_levels;
  textures.layout = VK_IMAGE_LAYOUT_GENERAL;
  textures.width = image_.info().width;
  textures.height = image_.info().height;
  textures.periodic_overlap = periodic_overlap_;
  textures.layers = layers();
  return textures;
}

std::vector<std::uint32_t> ResidentImages::layers() const {
  std::vector<std::uint32_t> out(subspaces_, std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t s : resident_) out[s] = s;
  return out;
}

}  // namespace carbtf
