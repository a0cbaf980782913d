#include "carbtf/engine/vulkan/buffer.hpp"

#include <algorithm>

#include "vulkan/vk_check.hpp"

namespace carbtf {

namespace {

// Allocates memory for `requirements` with the properties `usage` asks for (falling back to any
// host-visible type for readback when no cached one exists).
Status allocate(const Context& context, const VkMemoryRequirements& requirements, MemoryUsage usage,
                UniqueHandle<VkDeviceMemory>& memory, VkMemoryPropertyFlags& properties) {
  std::uint32_t type = 0;
  bool found = false;
  switch (usage) {
    case MemoryUsage::device_local:
      properties = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUsage::host_readback:
      properties = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      found = context.find_memory_type(requirements.memoryTypeBits, properties, type);
      if (!found) properties = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
      break;
    case MemoryUsage::host_upload:
      properties = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
  }
  if (!found && !context.find_memory_type(requirements.memoryTypeBits, properties, type)) {
    return {ErrorCode::device_unsuitable, "the device has no memory type for this buffer or image"};
  }
  auto allocate_info = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  allocate_info.allocationSize = requirements.size;
  allocate_info.memoryTypeIndex = type;
  VkDeviceMemory handle = VK_NULL_HANDLE;
  CARBTF_VK_TRY(context.vk().vkAllocateMemory(context.device(), &allocate_info, nullptr, &handle));
  memory = UniqueHandle<VkDeviceMemory>(&context.vk(), context.device(), handle);
  VkPhysicalDeviceMemoryProperties all{};
  context.vk().vkGetPhysicalDeviceMemoryProperties(context.physical_device(), &all);
  properties = all.memoryTypes[type].propertyFlags;
  return {};
}

}  // namespace

Status Buffer::create(const Context& context, const BufferCreateInfo& info, Buffer& out) noexcept {
  if (info.size == 0) return {ErrorCode::invalid_argument, "a buffer needs a size above 0"};
  const VulkanFunctions& vk = context.vk();
  Buffer buffer;
  buffer.context_ = &context;
  buffer.size_ = info.size;

  auto create = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  create.size = info.size;
  create.usage = info.usage;
  create.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer handle = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk.vkCreateBuffer(context.device(), &create, nullptr, &handle));
  buffer.buffer_ = UniqueHandle<VkBuffer>(&vk, context.device(), handle);
  context.set_debug_name(buffer.buffer_, info.debug_name);

  VkMemoryRequirements requirements{};
  vk.vkGetBufferMemoryRequirements(context.device(), handle, &requirements);
  VkMemoryPropertyFlags properties = 0;
  CARBTF_TRY(allocate(context, requirements, info.memory, buffer.memory_, properties));
  context.set_debug_name(buffer.memory_, info.debug_name);
  CARBTF_VK_TRY(vk.vkBindBufferMemory(context.device(), handle, buffer.memory_.get(), 0));
  if (properties & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    CARBTF_VK_TRY(
        vk.vkMapMemory(context.device(), buffer.memory_.get(), 0, VK_WHOLE_SIZE, 0, &buffer.mapped_));
    buffer.coherent_ = properties & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  }
  out = std::move(buffer);
  return {};
}

Status Buffer::invalidate_for_host_read() const noexcept {
  if (!mapped_ || coherent_) return {};
  auto range = vk_struct<VkMappedMemoryRange>(VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE);
  range.memory = memory_.get();
  range.offset = 0;
  range.size = VK_WHOLE_SIZE;
  CARBTF_VK_TRY(context_->vk().vkInvalidateMappedMemoryRanges(context_->device(), 1, &range));
  return {};
}

Status Image::create(const Context& context, const ImageCreateInfo& info, Image& out) noexcept {
  if (info.width == 0 || info.height == 0 || info.array_layers == 0) {
    return {ErrorCode::invalid_argument, "an image needs a width, height and layer count above 0"};
  }
  const VulkanFunctions& vk = context.vk();
  Image image;
  image.info_ = info;
  auto create = vk_struct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
  create.imageType = VK_IMAGE_TYPE_2D;
  create.format = info.format;
  create.extent = {info.width, info.height, 1};
  create.mipLevels = std::max(info.mip_levels, 1u);
  create.arrayLayers = info.array_layers;
  create.samples = VK_SAMPLE_COUNT_1_BIT;
  create.tiling = VK_IMAGE_TILING_OPTIMAL;
  create.usage = info.usage;
  create.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  create.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage handle = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk.vkCreateImage(context.device(), &create, nullptr, &handle));
  image.image_ = UniqueHandle<VkImage>(&vk, context.device(), handle);
  context.set_debug_name(image.image_, info.debug_name);

  VkMemoryRequirements requirements{};
  vk.vkGetImageMemoryRequirements(context.device(), handle, &requirements);
  VkMemoryPropertyFlags properties = 0;
  CARBTF_TRY(allocate(context, requirements, MemoryUsage::device_local, image.memory_, properties));
  context.set_debug_name(image.memory_, info.debug_name);
  CARBTF_VK_TRY(vk.vkBindImageMemory(context.device(), handle, image.memory_.get(), 0));

  auto view_info = vk_struct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
  view_info.image = handle;
  view_info.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  view_info.format = info.format;
  const bool depth = info.format == VK_FORMAT_D32_SFLOAT || info.format == VK_FORMAT_D16_UNORM;
  view_info.subresourceRange = {
      depth ? VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT} : VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT},
      0, std::max(info.mip_levels, 1u), 0, info.array_layers};
  VkImageView view = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk.vkCreateImageView(context.device(), &view_info, nullptr, &view));
  image.view_ = UniqueHandle<VkImageView>(&vk, context.device(), view);
  context.set_debug_name(image.view_, info.debug_name);
  if (create.mipLevels > 1) {
    view_info.subresourceRange.levelCount = 1;
    VkImageView level0 = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreateImageView(context.device(), &view_info, nullptr, &level0));
    image.level0_view_ = UniqueHandle<VkImageView>(&vk, context.device(), level0);
    context.set_debug_name(image.level0_view_, info.debug_name);
  }
  out = std::move(image);
  return {};
}

}  // namespace carbtf
