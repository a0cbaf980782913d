// Internal: finding the system Vulkan loader at run time and filling the function table from it.
#pragma once

#include "carbtf/engine/status.hpp"
#include "carbtf/engine/vulkan/vulkan_functions.hpp"

namespace carbtf::detail {

// dlopen()s libvulkan.so.1; `library` receives the handle to pass to close_vulkan_loader().
Status open_vulkan_loader(void*& library, PFN_vkGetInstanceProcAddr& get_instance_proc_addr) noexcept;
void close_vulkan_loader(void* library) noexcept;

// Fills the global (instance == null) entry points from vk.vkGetInstanceProcAddr.
Status load_global_functions(VulkanFunctions& vk) noexcept;
// Fills the instance-level entry points; debug-utils ones only when `debug_utils` is true.
Status load_instance_functions(VulkanFunctions& vk, VkInstance instance, bool debug_utils) noexcept;
// Fills the device-level entry points through vkGetDeviceProcAddr.
Status load_device_functions(VulkanFunctions& vk, VkDevice device) noexcept;

}  // namespace carbtf::detail
