// Internal: the engine's one way of writing a descriptor, pushed (compute kernels, the render pass's frame
// uniforms) or into a set (the material's). One descriptor per binding, as every carbtf layout has.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "carbtf/engine/vulkan/vulkan_functions.hpp"

namespace carbtf::detail {

// What one binding receives; exactly one of the pointers is set, matching `type`.
struct DescriptorResource {
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  const VkDescriptorBufferInfo* buffer = nullptr;
  const VkDescriptorImageInfo* image = nullptr;
  const VkBufferView* texel_buffer = nullptr;
};

// The write of `resource` to `binding` of `set` (VK_NULL_HANDLE for a pushed set).
inline VkWriteDescriptorSet descriptor_write(std::uint32_t binding, const DescriptorResource& resource,
                                             VkDescriptorSet set = VK_NULL_HANDLE) {
  auto write = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = resource.type;
  write.pBufferInfo = resource.buffer;
  write.pImageInfo = resource.image;
  write.pTexelBufferView = resource.texel_buffer;
  return write;
}

}  // namespace carbtf::detail
