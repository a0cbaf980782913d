// Move-only ownership of one Vulkan device object: destroys it (with the device's own table) when the
// owner goes away. The engine wraps only what it created; adopted host handles are never put in one.
// Not thread-safe: like the Vulkan objects themselves, a handle is externally synchronized.
#pragma once

#include <utility>

#include "carbtf/engine/vulkan/vulkan_functions.hpp"

namespace carbtf {

template <typename T>
struct HandleTraits;

#define CARBTF_HANDLE_TRAITS(Type, object_type, destroy_call)                               \
  template <>                                                                               \
  struct HandleTraits<Type> {                                                               \
    static constexpr VkObjectType kObjectType = object_type;                                \
    static void destroy(const VulkanFunctions& vk, VkDevice device, Type handle) noexcept { \
      vk.destroy_call(device, handle, nullptr);                                             \
    }                                                                                       \
  };
CARBTF_HANDLE_TRAITS(VkBuffer, VK_OBJECT_TYPE_BUFFER, vkDestroyBuffer)
CARBTF_HANDLE_TRAITS(VkImage, VK_OBJECT_TYPE_IMAGE, vkDestroyImage)
CARBTF_HANDLE_TRAITS(VkImageView, VK_OBJECT_TYPE_IMAGE_VIEW, vkDestroyImageView)
CARBTF_HANDLE_TRAITS(VkBufferView, VK_OBJECT_TYPE_BUFFER_VIEW, vkDestroyBufferView)
CARBTF_HANDLE_TRAITS(VkDeviceMemory, VK_OBJECT_TYPE_DEVICE_MEMORY, vkFreeMemory)
CARBTF_HANDLE_TRAITS(VkShaderModule, VK_OBJECT_TYPE_SHADER_MODULE, vkDestroyShaderModule)
CARBTF_HANDLE_TRAITS(VkDescriptorSetLayout, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT,
                     vkDestroyDescriptorSetLayout)
CARBTF_HANDLE_TRAITS(VkPipelineLayout, VK_OBJECT_TYPE_PIPELINE_LAYOUT, vkDestroyPipelineLayout)
CARBTF_HANDLE_TRAITS(VkPipeline, VK_OBJECT_TYPE_PIPELINE, vkDestroyPipeline)
CARBTF_HANDLE_TRAITS(VkCommandPool, VK_OBJECT_TYPE_COMMAND_POOL, vkDestroyCommandPool)
CARBTF_HANDLE_TRAITS(VkQueryPool, VK_OBJECT_TYPE_QUERY_POOL, vkDestroyQueryPool)
CARBTF_HANDLE_TRAITS(VkFence, VK_OBJECT_TYPE_FENCE, vkDestroyFence)
CARBTF_HANDLE_TRAITS(VkSampler, VK_OBJECT_TYPE_SAMPLER, vkDestroySampler)
CARBTF_HANDLE_TRAITS(VkDescriptorPool, VK_OBJECT_TYPE_DESCRIPTOR_POOL, vkDestroyDescriptorPool)
CARBTF_HANDLE_TRAITS(VkRenderPass, VK_OBJECT_TYPE_RENDER_PASS, vkDestroyRenderPass)
CARBTF_HANDLE_TRAITS(VkFramebuffer, VK_OBJECT_TYPE_FRAMEBUFFER, vkDestroyFramebuffer)
#undef CARBTF_HANDLE_TRAITS

template <typename T>
class UniqueHandle {
 public:
  UniqueHandle() = default;
  UniqueHandle(const VulkanFunctions* vk, VkDevice device, T handle) noexcept
      : vk_(vk), device_(device), handle_(handle) {}
  ~UniqueHandle() { reset(); }

  UniqueHandle(const UniqueHandle&) = delete;
  UniqueHandle& operator=(const UniqueHandle&) = delete;
  UniqueHandle(UniqueHandle&& other) noexcept
      : vk_(other.vk_), device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  UniqueHandle& operator=(UniqueHandle&& other) noexcept {
    if (this != &other) {
      reset();
      vk_ = other.vk_;
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }

  T get() const noexcept { return handle_; }
  explicit operator bool() const noexcept { return handle_ != VK_NULL_HANDLE; }

  void reset() noexcept {
    if (handle_ != VK_NULL_HANDLE) HandleTraits<T>::destroy(*vk_, device_, handle_);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  const VulkanFunctions* vk_ = nullptr;
  VkDevice device_ = VK_NULL_HANDLE;
  T handle_ = VK_NULL_HANDLE;
};

}  // namespace carbtf
