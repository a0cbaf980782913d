#include "vulkan/device_selection.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

namespace carbtf {

const char* device_type_name(VkPhysicalDeviceType type) noexcept {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

const std::vector<const char*>& required_device_extensions() {
  // Push descriptors let the engine record into a host's command buffers without owning descriptor
  // pools whose lifetime would have to track the host's frames.
  static const std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  return extensions;
}

namespace detail {

DeviceInfo describe_physical_device(const VulkanFunctions& vk, VkPhysicalDevice device, std::uint32_t index) {
  DeviceInfo info;
  info.index = index;

  auto subgroup =
      vk_struct<VkPhysicalDeviceSubgroupProperties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES);
  auto properties2 = vk_struct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
  properties2.pNext = &subgroup;
  vk.vkGetPhysicalDeviceProperties2(device, &properties2);
  const VkPhysicalDeviceProperties& p = properties2.properties;
  info.name = p.deviceName;
  info.type = p.deviceType;
  info.api_version = p.apiVersion;
  info.vendor_id = p.vendorID;
  info.device_id = p.deviceID;
  info.timestamp_period_ns = p.limits.timestampPeriod;
  info.max_storage_buffer_range = p.limits.maxStorageBufferRange;
  info.min_storage_buffer_offset_alignment = p.limits.minStorageBufferOffsetAlignment;
  std::copy_n(p.limits.maxComputeWorkGroupCount, 3, info.max_compute_group_count);
  info.max_image_dimension_2d = p.limits.maxImageDimension2D;
  info.max_image_array_layers = p.limits.maxImageArrayLayers;
  info.max_compute_shared_memory = p.limits.maxComputeSharedMemorySize;
  info.subgroup_size = subgroup.subgroupSize;

  VkPhysicalDeviceFeatures features{};
  vk.vkGetPhysicalDeviceFeatures(device, &features);
  info.shader_float64 = features.shaderFloat64 == VK_TRUE;

  // Prefer a family that does graphics and compute (the render pass will want both), else compute.
  std::uint32_t family_count = 0;
  vk.vkGetPhysicalDeviceQueueFamilyProperties(device, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vk.vkGetPhysicalDeviceQueueFamilyProperties(device, &family_count, families.data());
  int chosen = -1;
  for (std::uint32_t i = 0; i < family_count; ++i) {
    const VkQueueFlags flags = families[i].queueFlags;
    if (!(flags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (chosen < 0 || (flags & VK_QUEUE_GRAPHICS_BIT)) {
      chosen = static_cast<int>(i);
      if (flags & VK_QUEUE_GRAPHICS_BIT) break;
    }
  }

  std::uint32_t extension_count = 0;
  vk.vkEnumerateDeviceExtensionProperties(device, nullptr, &extension_count, nullptr);
  std::vector<VkExtensionProperties> extensions(extension_count);
  vk.vkEnumerateDeviceExtensionProperties(device, nullptr, &extension_count, extensions.data());
  std::string missing;
  for (const char* required : required_device_extensions()) {
    const bool found = std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
      return std::strcmp(e.extensionName, required) == 0;
    });
    if (!found) missing += (missing.empty() ? "" : ", ") + std::string(required);
  }

  if (VK_API_VERSION_MAJOR(info.api_version) == 1 && VK_API_VERSION_MINOR(info.api_version) < 2) {
    info.unsuitable_reason = "supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(info.api_version)) +
                             "." + std::to_string(VK_API_VERSION_MINOR(info.api_version)) +
                             ", carbtf needs 1.2";
  } else if (chosen < 0) {
    info.unsuitable_reason = "has no compute queue";
  } else if (!missing.empty()) {
    info.unsuitable_reason = "lacks " + missing;
  } else {
    info.suitable = true;
    info.queue_family_index = static_cast<std::uint32_t>(chosen);
    info.timestamp_valid_bits = families[info.queue_family_index].timestampValidBits;
  }
  return info;
}

std::string effective_selector(const std::string& selector, std::string& origin) {
  if (!selector.empty()) {
    origin = "device selector";
    return selector;
  }
  const char* from_environment = std::getenv("CARBTF_DEVICE");
  if (from_environment && *from_environment) {
    origin = "CARBTF_DEVICE";
    return from_environment;
  }
  origin.clear();
  return {};
}

}  // namespace detail

namespace {

int type_preference(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 1;
    default:
      return 0;
  }
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string device_list(const std::vector<DeviceInfo>& devices) {
  std::string list;
  for (const DeviceInfo& d : devices) {
    list += (list.empty() ? "" : ", ") + std::to_string(d.index) + ": " + d.name + " (" +
            device_type_name(d.type) + (d.suitable ? "" : ", unsuitable: " + d.unsuitable_reason) + ")";
  }
  return list;
}

}  // namespace

Status select_device(const std::vector<DeviceInfo>& devices, const std::string& selector,
                     std::uint32_t& index) noexcept {
  try {
    if (devices.empty()) {
      return {
          ErrorCode::vulkan_driver_missing,
          "no Vulkan device found: install a Vulkan driver (Debian: apt-get install mesa-vulkan-drivers for "
          "Vulkan on the CPU, or your GPU vendor's driver)"};
    }
    std::string origin;
    const std::string wanted = detail::effective_selector(selector, origin);
    if (wanted.empty()) {
      const DeviceInfo* best = nullptr;
      for (const DeviceInfo& d : devices) {
        if (d.suitable && (!best || type_preference(d.type) > type_preference(best->type))) best = &d;
      }
      if (!best) {
        return {ErrorCode::device_unsuitable, "no Vulkan device can run carbtf: " + device_list(devices)};
      }
      index = best->index;
      return {};
    }

    const DeviceInfo* match = nullptr;
    const bool numeric =
        std::all_of(wanted.begin(), wanted.end(), [](unsigned char c) { return std::isdigit(c); });
    if (numeric) {
      const unsigned long wanted_index = std::strtoul(wanted.c_str(), nullptr, 10);
      for (const DeviceInfo& d : devices) {
        if (d.index == wanted_index) match = &d;
      }
    } else {
      const std::string needle = lower(wanted);
      for (const DeviceInfo& d : devices) {
        if (lower(d.name).find(needle) == std::string::npos) continue;
        if (!match || (d.suitable && !match->suitable)) match = &d;
      }
    }
    if (!match) {
      return {ErrorCode::device_not_found,
              origin + " '" + wanted + "' matches no Vulkan device; devices are " + device_list(devices)};
    }
    if (!match->suitable) {
      return {ErrorCode::device_unsuitable,
              origin + " '" + wanted + "' picks " + match->name + ", which " + match->unsuitable_reason};
    }
    index = match->index;
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while selecting a device"};
  }
}

}  // namespace carbtf
