// Internal: describing physical devices and choosing one.
#pragma once

#include <string>
#include <vector>

#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf::detail {

DeviceInfo describe_physical_device(const VulkanFunctions& vk, VkPhysicalDevice device, std::uint32_t index);

// Resolves an empty selector to $CARBTF_DEVICE; `origin` receives where the selector came from,
// for messages ("--device", "CARBTF_DEVICE" or "" for the automatic choice).
std::string effective_selector(const std::string& selector, std::string& origin);

}  // namespace carbtf::detail
