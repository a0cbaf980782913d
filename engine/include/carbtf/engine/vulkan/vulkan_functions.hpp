// The Vulkan entry points the engine calls, loaded at run time through vkGetInstanceProcAddr and
// vkGetDeviceProcAddr. The engine never calls a Vulkan symbol directly: a host engine that loads Vulkan
// its own way (volk, a custom loader, a layer) hands over its vkGetInstanceProcAddr and every call goes
// through it. One table per context; read-only after loading, so any thread may use it.
#pragma once

#include <vulkan/vulkan.h>

namespace carbtf {

// X(name): commands resolved with a null instance.
#define CARBTF_VK_GLOBAL_FUNCTIONS(X)   \
  X(vkCreateInstance)                   \
  X(vkEnumerateInstanceVersion)         \
  X(vkEnumerateInstanceLayerProperties) \
  X(vkEnumerateInstanceExtensionProperties)

#define CARBTF_VK_INSTANCE_FUNCTIONS(X)       \
  X(vkDestroyInstance)                        \
  X(vkEnumeratePhysicalDevices)               \
  X(vkGetPhysicalDeviceProperties)            \
  X(vkGetPhysicalDeviceProperties2)           \
  X(vkGetPhysicalDeviceFeatures)              \
  X(vkGetPhysicalDeviceQueueFamilyProperties) \
  X(vkGetPhysicalDeviceMemoryProperties)      \
  X(vkGetPhysicalDeviceFormatProperties)      \
  X(vkEnumerateDeviceExtensionProperties)     \
  X(vkCreateDevice)                           \
  X(vkGetDeviceProcAddr)

// Present only when the instance enabled VK_EXT_debug_utils; may stay null.
#define CARBTF_VK_DEBUG_UTILS_FUNCTIONS(X) \
  X(vkCreateDebugUtilsMessengerEXT)        \
  X(vkDestroyDebugUtilsMessengerEXT)       \
  X(vkSetDebugUtilsObjectNameEXT)

#define CARBTF_VK_DEVICE_FUNCTIONS(X) \
  X(vkDestroyDevice)                  \
  X(vkGetDeviceQueue)                 \
  X(vkDeviceWaitIdle)                 \
  X(vkQueueSubmit)                    \
  X(vkCreateBuffer)                   \
  X(vkDestroyBuffer)                  \
  X(vkGetBufferMemoryRequirements)    \
  X(vkCreateImage)                    \
  X(vkDestroyImage)                   \
  X(vkCreateImageView)                \
  X(vkDestroyImageView)               \
  X(vkCreateBufferView)               \
  X(vkDestroyBufferView)              \
  X(vkGetImageMemoryRequirements)     \
  X(vkAllocateMemory)                 \
  X(vkFreeMemory)                     \
  X(vkBindBufferMemory)               \
  X(vkBindImageMemory)                \
  X(vkMapMemory)                      \
  X(vkUnmapMemory)                    \
  X(vkInvalidateMappedMemoryRanges)   \
  X(vkCreateShaderModule)             \
  X(vkDestroyShaderModule)            \
  X(vkCreateDescriptorSetLayout)      \
  X(vkDestroyDescriptorSetLayout)     \
  X(vkCreatePipelineLayout)           \
  X(vkDestroyPipelineLayout)          \
  X(vkCreateComputePipelines)         \
  X(vkDestroyPipeline)                \
  X(vkCreateCommandPool)              \
  X(vkDestroyCommandPool)             \
  X(vkResetCommandPool)               \
  X(vkAllocateCommandBuffers)         \
  X(vkBeginCommandBuffer)             \
  X(vkEndCommandBuffer)               \
  X(vkCreateFence)                    \
  X(vkDestroyFence)                   \
  X(vkWaitForFences)                  \
  X(vkResetFences)                    \
  X(vkCreateQueryPool)                \
  X(vkDestroyQueryPool)               \
  X(vkGetQueryPoolResults)            \
  X(vkCmdBindPipeline)                \
  X(vkCmdPushConstants)               \
  X(vkCmdPushDescriptorSetKHR)        \
  X(vkCmdDispatch)                    \
  X(vkCmdPipelineBarrier)             \
  X(vkCmdFillBuffer)                  \
  X(vkCmdCopyBuffer)                  \
  X(vkCmdCopyImageToBuffer)           \
  X(vkCmdCopyImage)                   \
  X(vkCmdBlitImage)                   \
  X(vkCmdClearColorImage)             \
  X(vkCmdResetQueryPool)              \
  X(vkCmdWriteTimestamp)              \
  X(vkCreateSampler)                  \
  X(vkDestroySampler)                 \
  X(vkCreateDescriptorPool)           \
  X(vkDestroyDescriptorPool)          \
  X(vkAllocateDescriptorSets)         \
  X(vkUpdateDescriptorSets)           \
  X(vkCmdBindDescriptorSets)          \
  X(vkCmdCopyBufferToImage)           \
  X(vkCreateRenderPass)               \
  X(vkDestroyRenderPass)              \
  X(vkCreateFramebuffer)              \
  X(vkDestroyFramebuffer)             \
  X(vkCreateGraphicsPipelines)        \
  X(vkCmdBeginRenderPass)             \
  X(vkCmdEndRenderPass)               \
  X(vkCmdBindVertexBuffers)           \
  X(vkCmdBindIndexBuffer)             \
  X(vkCmdDrawIndexed)                 \
  X(vkCmdSetViewport)                 \
  X(vkCmdSetScissor)

struct VulkanFunctions {
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
#define CARBTF_VK_DECLARE(name) PFN_##name name = nullptr;
  CARBTF_VK_GLOBAL_FUNCTIONS(CARBTF_VK_DECLARE)
  CARBTF_VK_INSTANCE_FUNCTIONS(CARBTF_VK_DECLARE)
  CARBTF_VK_DEBUG_UTILS_FUNCTIONS(CARBTF_VK_DECLARE)
  CARBTF_VK_DEVICE_FUNCTIONS(CARBTF_VK_DECLARE)
#undef CARBTF_VK_DECLARE
};

// A zero-initialized Vulkan info struct with its sType set (clean under -Wextra, unlike `T{sType}`).
template <typename T>
constexpr T vk_struct(VkStructureType type) noexcept {
  T value{};
  value.sType = type;
  return value;
}

}  // namespace carbtf
