// The engine's Vulkan context: either its own headless instance and device, or a host engine's
// adopted handles. A context destroys exactly what it created (its instance, messenger and device
// when it made them; its command pool and fence always) and never a handle it was given.
//
// Thread safety: const member functions may be called from any thread. submit_and_wait() records
// into the context's single command pool and submits to the queue, so it is externally synchronized,
// like the VkQueue it uses; a host that submits to the same queue from another thread must serialize
// with it. Lifetime: every object created from a context (buffers, generators) must be destroyed
// before the context.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "carbtf/engine/status.hpp"
#include "carbtf/engine/vulkan/unique_handle.hpp"
#include "carbtf/engine/vulkan/vulkan_functions.hpp"

namespace carbtf {

// What a physical device offers, and whether carbtf can run on it.
struct DeviceInfo {
  std::uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::uint32_t api_version = 0;
  std::uint32_t vendor_id = 0;
  std::uint32_t device_id = 0;
  std::uint32_t queue_family_index = 0;    // the compute-capable family carbtf uses
  std::uint32_t timestamp_valid_bits = 0;  // 0: no timestamps on that family
  float timestamp_period_ns = 0.0f;
  VkDeviceSize max_storage_buffer_range = 0;
  VkDeviceSize min_storage_buffer_offset_alignment = 0;
  std::uint32_t max_compute_group_count[3] = {0, 0, 0};
  std::uint32_t max_image_dimension_2d = 0;
  std::uint32_t max_image_array_layers = 0;
  std::uint32_t max_compute_shared_memory = 0;
  std::uint32_t subgroup_size = 0;
  bool shader_float64 = false;
  bool suitable = false;
  std::string unsuitable_reason;  // why not, when !suitable
};

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU" or "other".
const char* device_type_name(VkPhysicalDeviceType type) noexcept;

// Device extensions carbtf needs; a host engine that wants to adopt must enable these on its device.
const std::vector<const char*>& required_device_extensions();

enum class MessageSeverity { verbose, info, warning, error };

// Counts of validation-layer and loader messages seen by the context's debug messenger.
struct ValidationReport {
  std::uint32_t warnings = 0;
  std::uint32_t errors = 0;
  std::vector<std::string> messages;  // the first warnings and errors, for reporting

  bool clean() const noexcept { return warnings == 0 && errors == 0; }
};

struct ContextCreateInfo {
  // Enable VK_LAYER_KHRONOS_validation and count its messages (tests always do).
  bool enable_validation = false;
  // With validation: also enable synchronization validation.
  bool synchronization_validation = true;
  // Which device: empty means the CARBTF_DEVICE environment variable, and if that is unset or empty
  // the best suitable device (discrete > integrated > virtual > CPU). A selector is either a device
  // index as listed by `carbtf devices` or a case-insensitive part of the device name ("llvmpipe").
  std::string device_selector;
  // Called for every warning or error message, from whichever thread the driver reports on.
  std::function<void(MessageSeverity, const char*)> on_message;
  std::string application_name = "carbtf";
};

// A host engine's handles. The context uses them and never destroys them; they must outlive it.
struct AdoptInfo {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;      // created with required_device_extensions() enabled
  std::uint32_t queue_family_index = 0;  // must support compute
  VkQueue queue = VK_NULL_HANDLE;
  // The host's loader entry point; null means the system loader (libvulkan.so.1).
  PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
  // True when the host enabled VK_EXT_debug_utils on its instance: carbtf then names its objects.
  bool debug_utils_enabled = false;
};

class Context {
 public:
  // Creates a headless instance and device of its own.
  static Status create(const ContextCreateInfo& info, std::unique_ptr<Context>& out) noexcept;
  // Uses a host engine's instance, device and queue.
  static Status adopt(const AdoptInfo& info, std::unique_ptr<Context>& out) noexcept;
  ~Context();

  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const VulkanFunctions& vk() const noexcept { return vk_; }
  VkInstance instance() const noexcept { return instance_; }
  VkPhysicalDevice physical_device() const noexcept { return physical_device_; }
  VkDevice device() const noexcept { return device_; }
  VkQueue queue() const noexcept { return queue_; }
  std::uint32_t queue_family_index() const noexcept { return device_info_.queue_family_index; }
  const DeviceInfo& device_info() const noexcept { return device_info_; }
  bool owns_device() const noexcept { return owns_device_; }

  // Index of a memory type with all of `required` among `type_bits`; false when there is none.
  bool find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                        std::uint32_t& index) const noexcept;

  // Gives a Vulkan object a name shown by validation messages and debuggers (no-op without debug utils).
  void set_debug_name(VkObjectType type, std::uint64_t handle, const char* name) const noexcept;
  template <typename T>
  void set_debug_name(const UniqueHandle<T>& handle, const char* name) const noexcept {
    set_debug_name(HandleTraits<T>::kObjectType, reinterpret_cast<std::uint64_t>(handle.get()), name);
  }

  // Convenience for tools: records with `record` into a fresh command buffer, submits it and waits.
  // `record` must not throw; its failure Status is returned without submitting.
  Status submit_and_wait(const std::function<Status(VkCommandBuffer)>& record) noexcept;

  // Messages seen so far by this context's messenger (own contexts with validation only).
  ValidationReport validation_report() const;

 private:
  Context();
  struct Messenger;

  Status create_own(const ContextCreateInfo& info);
  Status adopt_handles(const AdoptInfo& info);
  Status load_device_functions();
  Status create_submit_resources();

  VulkanFunctions vk_{};
  void* loader_library_ = nullptr;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  bool owns_instance_ = false;
  bool owns_device_ = false;
  bool debug_utils_ = false;
  DeviceInfo device_info_{};
  std::unique_ptr<Messenger> messenger_;
  UniqueHandle<VkCommandPool> command_pool_;
  UniqueHandle<VkFence> fence_;
  VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;
};

// Lists every physical device (through a temporary instance), with carbtf's verdict on each.
Status enumerate_devices(std::vector<DeviceInfo>& out) noexcept;

// The index that `selector` (see ContextCreateInfo::device_selector) picks among `devices`.
Status select_device(const std::vector<DeviceInfo>& devices, const std::string& selector,
                     std::uint32_t& index) noexcept;

}  // namespace carbtf
