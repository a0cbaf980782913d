#include "carbtf/engine/vulkan/texture_array.hpp"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "carbtf/engine/vulkan/mip_chain.hpp"
#include "vulkan/barriers.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {

Status TextureArray::create(Context& context, std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                            VkFormat format, std::unique_ptr<TextureArray>& out, std::uint32_t mip_levels,
                            bool host_levels) noexcept {
  try {
    std::uint32_t texel_bytes = 0;
    switch (format) {
      case VK_FORMAT_R8G8B8A8_SRGB:
      case VK_FORMAT_R8G8B8A8_UNORM:
      case VK_FORMAT_R32_SFLOAT:
        texel_bytes = 4;
        break;
      case VK_FORMAT_R32G32_SFLOAT:
        texel_bytes = 8;
        break;
      case VK_FORMAT_R32G32B32A32_SFLOAT:
        texel_bytes = 16;
        break;
      default:
        return {ErrorCode::invalid_argument,
                "a texture array holds RGBA8 (sRGB or UNORM), R32F, RG32F or RGBA32F texels"};
    }
    const DeviceInfo& device = context.device_info();
    if (width == 0 || height == 0 || layers == 0 || width > device.max_image_dimension_2d ||
        height > device.max_image_dimension_2d || layers > device.max_image_array_layers) {
      return {ErrorCode::invalid_argument, "a texture array of " + std::to_string(width) + "x" +
                                               std::to_string(height) + "x" + std::to_string(layers) +
                                               " is beyond this device's image limits"};
    }
    std::unique_ptr<TextureArray> array(new TextureArray());
    array->context_ = &context;
    array->texel_bytes_ = texel_bytes;
    array->host_levels_ = host_levels;
    ImageCreateInfo info;
    info.width = width;
    info.height = height;
    info.array_layers = layers;
    info.format = format;
    const std::uint32_t possible = can_blit_mips(context, format) ? mip_level_count(width, height) : 1;
    info.mip_levels = mip_levels == 0 ? possible : std::min(mip_levels, possible);
    info.usage =
        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    info.debug_name = "carbtf texture array";
    CARBTF_TRY(Image::create(context, info, array->image_));
    // Past the last staged level: the staging memory's size.
    const std::uint32_t staged_levels = host_levels ? info.mip_levels : 1;
    CARBTF_TRY(Buffer::create(context,
                              {array->staging_offset(0, staged_levels), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               MemoryUsage::host_upload, "carbtf texture array staging"},
                              array->staging_));
    out = std::move(array);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while creating a texture array"};
  }
}

TextureArray::~TextureArray() = default;

std::size_t TextureArray::staging_offset(std::uint32_t layer, std::uint32_t level) const noexcept {
  std::size_t offset = 0;
  for (std::uint32_t l = 0; l < level; ++l)
    offset += std::size_t{width() >> l} * (height() >> l) * layers() * texel_bytes_;
  return offset + std::size_t{width() >> level} * (height() >> level) * layer * texel_bytes_;
}

Status TextureArray::set_layer(std::uint32_t layer, std::span<const std::uint8_t> texels) noexcept {
  const std::size_t layer_bytes = std::size_t{width()} * height() * texel_bytes_;
  if (layer >= layers() || texels.size() != layer_bytes) {
    return {ErrorCode::invalid_argument, "texture array layer " + std::to_string(layer) + " needs " +
                                             std::to_string(layer_bytes) + " bytes, got " +
                                             std::to_string(texels.size())};
  }
  std::memcpy(static_cast<std::uint8_t*>(staging_.mapped()) + staging_offset(layer, 0), texels.data(),
              layer_bytes);
  return {};
}

Status TextureArray::set_level(std::uint32_t layer, std::uint32_t level,
                               std::span<const std::uint8_t> texels) noexcept {
  if (!host_levels_ || level == 0 || level >= mip_levels()) {
    return {
        ErrorCode::invalid_argument,
        "texture array level " + std::to_string(level) +
            (host_levels_ ? " is not a level above 0 of this array"
                          : " is made by the upload's blits (the array was not created with host levels)")};
  }
  const std::size_t level_bytes = std::size_t{width() >> level} * (height() >> level) * texel_bytes_;
  if (layer >= layers() || texels.size() != level_bytes) {
    return {ErrorCode::invalid_argument, "texture array layer " + std::to_string(layer) + " level " +
                                             std::to_string(level) + " needs " + std::to_string(level_bytes) +
                                             " bytes, got " + std::to_string(texels.size())};
  }
  std::memcpy(static_cast<std::uint8_t*>(staging_.mapped()) + staging_offset(layer, level), texels.data(),
              level_bytes);
  return {};
}

Status TextureArray::record_upload(VkCommandBuffer cb) const noexcept {
  const VulkanFunctions& vk = context_->vk();
  const VkImage image = image_.handle();
  const std::uint32_t copied_levels = host_levels_ ? mip_levels() : 1;
  const detail::ColourRange copied{0, copied_levels, 0, layers()};
  const detail::StageAccess upload{VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT};
  // Earlier draws may still read the image: the stages order the upload after them.
  detail::transition_colour(vk, cb, image, copied, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, {VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0},
                            upload);
  for (std::uint32_t level = 0; level < copied_levels; ++level) {
    VkBufferImageCopy copy{};
    copy.bufferOffset = staging_offset(0, level);
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, layers()};
    copy.imageExtent = {width() >> level, height() >> level, 1};
    vk.vkCmdCopyBufferToImage(cb, staging_.handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  }
  VkImageLayout last_layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  detail::StageAccess last = upload;
  if (!host_levels_ && mip_levels() > 1) {
    // Level 0 is the blits' source, then read by shaders like the rest.
    const detail::StageAccess blit_source{VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT};
    detail::transition_colour(vk, cb, image, copied, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, upload, blit_source);
    std::vector<std::uint32_t> all(layers());
    for (std::uint32_t i = 0; i < layers(); ++i) all[i] = i;
    CARBTF_TRY(record_mip_blits(*context_, cb,
                                {image, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, width(), height()}, image, 1,
                                mip_levels() - 1, all, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
    last_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    last = blit_source;
  }
  detail::transition_colour(vk, cb, image, copied, last_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                            last,
                            {VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                             VK_ACCESS_SHADER_READ_BIT});
  return {};
}

Status TextureArray::upload_and_wait() noexcept {
  return context_->submit_and_wait([this](VkCommandBuffer cb) { return record_upload(cb); });
}

}  // namespace carbtf
