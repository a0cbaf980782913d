#include "vulkan/vulkan_loader.hpp"

#include <dlfcn.h>

#include <string>

namespace carbtf::detail {

Status open_vulkan_loader(void*& library, PFN_vkGetInstanceProcAddr& get_instance_proc_addr) noexcept {
  library = nullptr;
  for (const char* name : {"libvulkan.so.1", "libvulkan.so"}) {
    library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (library) break;
  }
  if (!library) {
    return {ErrorCode::vulkan_loader_missing,
            "cannot load the Vulkan loader libvulkan.so.1: install it (Debian: apt-get install libvulkan1 "
            "mesa-vulkan-drivers)"};
  }
  get_instance_proc_addr =
      reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library, "vkGetInstanceProcAddr"));
  if (!get_instance_proc_addr) {
    dlclose(library);
    library = nullptr;
    return {ErrorCode::vulkan_loader_missing,
            "libvulkan.so.1 has no vkGetInstanceProcAddr: broken Vulkan loader"};
  }
  return {};
}

void close_vulkan_loader(void* library) noexcept {
  if (library) dlclose(library);
}

namespace {

template <typename Pfn>
Status resolve(Pfn& slot, PFN_vkVoidFunction function, const char* name, bool required) {
  slot = reinterpret_cast<Pfn>(function);
  if (!slot && required) {
    return {ErrorCode::device_unsuitable, std::string("the Vulkan implementation does not provide ") + name};
  }
  return {};
}

}  // namespace

Status load_global_functions(VulkanFunctions& vk) noexcept {
#define CARBTF_LOAD(name)                                                                                 \
  if (Status s = resolve(vk.name, vk.vkGetInstanceProcAddr(VK_NULL_HANDLE, #name), #name, true); !s.ok()) \
    return s;
  CARBTF_VK_GLOBAL_FUNCTIONS(CARBTF_LOAD)
#undef CARBTF_LOAD
  return {};
}

Status load_instance_functions(VulkanFunctions& vk, VkInstance instance, bool debug_utils) noexcept {
#define CARBTF_LOAD(name) \
  if (Status s = resolve(vk.name, vk.vkGetInstanceProcAddr(instance, #name), #name, true); !s.ok()) return s;
  CARBTF_VK_INSTANCE_FUNCTIONS(CARBTF_LOAD)
  if (debug_utils) {
    CARBTF_VK_DEBUG_UTILS_FUNCTIONS(CARBTF_LOAD)
  }
#undef CARBTF_LOAD
  return {};
}

Status load_device_functions(VulkanFunctions& vk, VkDevice device) noexcept {
#define CARBTF_LOAD(name) \
  if (Status s = resolve(vk.name, vk.vkGetDeviceProcAddr(device, #name), #name, true); !s.ok()) return s;
  CARBTF_VK_DEVICE_FUNCTIONS(CARBTF_LOAD)
#undef CARBTF_LOAD
  return {};
}

}  // namespace carbtf::detail
