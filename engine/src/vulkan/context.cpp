#include "carbtf/engine/vulkan/context.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
#include <new>

#include "vulkan/device_selection.hpp"
#include "vulkan/vk_check.hpp"
#include "vulkan/vulkan_loader.hpp"

namespace carbtf {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr std::size_t kKeptMessages = 32;
// Long enough for a 4096^2 synthesis on lavapipe; a GPU that takes longer is hung, not busy.
constexpr std::uint64_t kSubmitTimeoutNs = 600ull * 1000 * 1000 * 1000;

Status no_driver_status() {
  return {
      ErrorCode::vulkan_driver_missing,
      "no Vulkan driver found: install one (Debian: apt-get install mesa-vulkan-drivers for Vulkan on the "
      "CPU, or your GPU vendor's Vulkan driver)"};
}

template <typename Body>
Status guarded(const char* what, Body&& body) noexcept {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, std::string("out of host memory while ") + what};
  }
}

}  // namespace

// The debug messenger's state. The callback may run on any thread, hence the atomics and the mutex.
struct Context::Messenger {
  VkDebugUtilsMessengerEXT handle = VK_NULL_HANDLE;
  std::atomic<std::uint32_t> warnings{0};
  std::atomic<std::uint32_t> errors{0};
  std::mutex mutex;
  std::vector<std::string> messages;
  std::function<void(MessageSeverity, const char*)> on_message;

  static VKAPI_ATTR VkBool32 VKAPI_CALL callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                 void* user) {
    auto* self = static_cast<Messenger*>(user);
    const bool is_error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    (is_error ? self->errors : self->warnings).fetch_add(1, std::memory_order_relaxed);
    const char* text = data && data->pMessage ? data->pMessage : "(no message)";
    {
      std::lock_guard<std::mutex> lock(self->mutex);
      if (self->messages.size() < kKeptMessages) {
        try {
          self->messages.emplace_back(std::string(is_error ? "error: " : "warning: ") + text);
        } catch (...) {  // a lost message text must not unwind into the driver; the count stays
        }
      }
    }
    if (self->on_message)
      self->on_message(is_error ? MessageSeverity::error : MessageSeverity::warning, text);
    return VK_FALSE;  // never abort the call: the layer reports, the application decides
  }

  VkDebugUtilsMessengerCreateInfoEXT create_info() {
    auto info = vk_struct<VkDebugUtilsMessengerCreateInfoEXT>(
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = &Messenger::callback;
    info.pUserData = this;
    return info;
  }
};

Context::Context() = default;

Context::~Context() {
  // Our own objects first, while the device they belong to is certainly alive; submit_and_wait()
  // always waits, so none of them is still in use by the GPU.
  command_pool_.reset();
  fence_.reset();
  if (owns_device_ && device_) {
    vk_.vkDeviceWaitIdle(device_);
    vk_.vkDestroyDevice(device_, nullptr);
  }
  if (messenger_ && messenger_->handle)
    vk_.vkDestroyDebugUtilsMessengerEXT(instance_, messenger_->handle, nullptr);
  if (owns_instance_ && instance_) vk_.vkDestroyInstance(instance_, nullptr);
  detail::close_vulkan_loader(loader_library_);
}

Status Context::create(const ContextCreateInfo& info, std::unique_ptr<Context>& out) noexcept {
  return guarded("creating the Vulkan context", [&]() -> Status {
    std::unique_ptr<Context> context(new Context());
    CARBTF_TRY(context->create_own(info));
    out = std::move(context);
    return {};
  });
}

Status Context::adopt(const AdoptInfo& info, std::unique_ptr<Context>& out) noexcept {
  return guarded("adopting the host's Vulkan device", [&]() -> Status {
    std::unique_ptr<Context> context(new Context());
    CARBTF_TRY(context->adopt_handles(info));
    out = std::move(context);
    return {};
  });
}

namespace {

struct InstanceSetup {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  bool debug_utils = false;
};

Status plan_instance(const VulkanFunctions& vk, bool validation, InstanceSetup& setup) {
  std::uint32_t version = VK_API_VERSION_1_0;
  CARBTF_VK_TRY(vk.vkEnumerateInstanceVersion(&version));
  if (VK_API_VERSION_MAJOR(version) == 1 && VK_API_VERSION_MINOR(version) < 2) {
    return {ErrorCode::device_unsuitable, "the Vulkan loader supports only Vulkan 1." +
                                              std::to_string(VK_API_VERSION_MINOR(version)) +
                                              "; carbtf needs 1.2 (update libvulkan1)"};
  }
  std::uint32_t count = 0;
  CARBTF_VK_TRY(vk.vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  CARBTF_VK_TRY(vk.vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data()));
  setup.debug_utils = std::any_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) == 0;
  });
  if (setup.debug_utils) setup.extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  if (validation) {
    CARBTF_VK_TRY(vk.vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    CARBTF_VK_TRY(vk.vkEnumerateInstanceLayerProperties(&count, layers.data()));
    const bool found = std::any_of(layers.begin(), layers.end(), [](const VkLayerProperties& l) {
      return std::strcmp(l.layerName, kValidationLayer) == 0;
    });
    if (!found) {
      return {
          ErrorCode::validation_layer_missing,
          "Vulkan validation was requested but VK_LAYER_KHRONOS_validation is not installed (Debian: apt-get "
          "install vulkan-validationlayers)"};
    }
    if (!setup.debug_utils) {
      return {ErrorCode::validation_layer_missing,
              "Vulkan validation was requested but the loader lacks VK_EXT_debug_utils to report messages"};
    }
    setup.layers.push_back(kValidationLayer);
  }
  return {};
}

}  // namespace

Status Context::create_own(const ContextCreateInfo& info) {
  CARBTF_TRY(detail::open_vulkan_loader(loader_library_, vk_.vkGetInstanceProcAddr));
  CARBTF_TRY(detail::load_global_functions(vk_));

  InstanceSetup setup;
  CARBTF_TRY(plan_instance(vk_, info.enable_validation, setup));
  debug_utils_ = setup.debug_utils;

  auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = info.application_name.c_str();
  app.pEngineName = "carbtf";
  app.apiVersion = VK_API_VERSION_1_2;
  auto create = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  create.pApplicationInfo = &app;
  create.enabledLayerCount = static_cast<std::uint32_t>(setup.layers.size());
  create.ppEnabledLayerNames = setup.layers.data();
  create.enabledExtensionCount = static_cast<std::uint32_t>(setup.extensions.size());
  create.ppEnabledExtensionNames = setup.extensions.data();

  // Chained messenger: messages during vkCreateInstance/vkDestroyInstance are counted too.
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{};
  const VkValidationFeatureEnableEXT sync_validation =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  auto features = vk_struct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
  if (info.enable_validation) {
    messenger_ = std::make_unique<Messenger>();
    messenger_->on_message = info.on_message;
    messenger_info = messenger_->create_info();
    create.pNext = &messenger_info;
    if (info.synchronization_validation) {
      features.enabledValidationFeatureCount = 1;
      features.pEnabledValidationFeatures = &sync_validation;
      messenger_info.pNext = &features;
    }
  }
  const VkResult created = vk_.vkCreateInstance(&create, nullptr, &instance_);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER) return no_driver_status();
  CARBTF_VK_TRY(created);
  owns_instance_ = true;
  CARBTF_TRY(detail::load_instance_functions(vk_, instance_, debug_utils_));
  if (messenger_) {
    messenger_info.pNext = nullptr;  // the validation features belong to the instance chain only
    CARBTF_VK_TRY(
        vk_.vkCreateDebugUtilsMessengerEXT(instance_, &messenger_info, nullptr, &messenger_->handle));
  }

  std::uint32_t count = 0;
  const VkResult enumerated = vk_.vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  if (enumerated == VK_ERROR_INITIALIZATION_FAILED || (enumerated == VK_SUCCESS && count == 0)) {
    return no_driver_status();
  }
  CARBTF_VK_TRY(enumerated);
  std::vector<VkPhysicalDevice> physical_devices(count);
  CARBTF_VK_TRY(vk_.vkEnumeratePhysicalDevices(instance_, &count, physical_devices.data()));
  std::vector<DeviceInfo> devices;
  for (std::uint32_t i = 0; i < count; ++i) {
    devices.push_back(detail::describe_physical_device(vk_, physical_devices[i], i));
  }
  std::uint32_t chosen = 0;
  CARBTF_TRY(select_device(devices, info.device_selector, chosen));
  physical_device_ = physical_devices[chosen];
  device_info_ = devices[chosen];

  const float priority = 1.0f;
  auto queue_info = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  queue_info.queueFamilyIndex = device_info_.queue_family_index;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures enabled_features{};
  enabled_features.shaderFloat64 = device_info_.shader_float64 ? VK_TRUE : VK_FALSE;
  auto device_create = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  device_create.queueCreateInfoCount = 1;
  device_create.pQueueCreateInfos = &queue_info;
  device_create.enabledExtensionCount = static_cast<std::uint32_t>(required_device_extensions().size());
  device_create.ppEnabledExtensionNames = required_device_extensions().data();
  device_create.pEnabledFeatures = &enabled_features;
  CARBTF_VK_TRY(vk_.vkCreateDevice(physical_device_, &device_create, nullptr, &device_));
  owns_device_ = true;
  CARBTF_TRY(load_device_functions());
  vk_.vkGetDeviceQueue(device_, device_info_.queue_family_index, 0, &queue_);
  return create_submit_resources();
}

Status Context::adopt_handles(const AdoptInfo& info) {
  if (!info.instance || !info.physical_device || !info.device || !info.queue) {
    return {ErrorCode::invalid_argument,
            "AdoptInfo needs the host's instance, physical device, device and queue"};
  }
  if (info.get_instance_proc_addr) {
    vk_.vkGetInstanceProcAddr = info.get_instance_proc_addr;
  } else {
    CARBTF_TRY(detail::open_vulkan_loader(loader_library_, vk_.vkGetInstanceProcAddr));
  }
  CARBTF_TRY(detail::load_global_functions(vk_));
  instance_ = info.instance;
  physical_device_ = info.physical_device;
  device_ = info.device;
  queue_ = info.queue;
  debug_utils_ = info.debug_utils_enabled;
  CARBTF_TRY(detail::load_instance_functions(vk_, instance_, debug_utils_));

  device_info_ = detail::describe_physical_device(vk_, physical_device_, 0);
  std::uint32_t family_count = 0;
  vk_.vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vk_.vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
  if (info.queue_family_index >= family_count ||
      !(families[info.queue_family_index].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
    return {
        ErrorCode::invalid_argument,
        "the adopted queue family " + std::to_string(info.queue_family_index) + " does not support compute"};
  }
  device_info_.queue_family_index = info.queue_family_index;
  device_info_.timestamp_valid_bits = families[info.queue_family_index].timestampValidBits;
  if (Status s = load_device_functions(); !s.ok()) {
    return {ErrorCode::device_unsuitable,
            s.message() + "; create the adopted device with carbtf::required_device_extensions() enabled"};
  }
  return create_submit_resources();
}

Status Context::load_device_functions() {
  return detail::load_device_functions(vk_, device_);
}

Status Context::create_submit_resources() {
  auto pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pool_info.queueFamilyIndex = device_info_.queue_family_index;
  VkCommandPool pool = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk_.vkCreateCommandPool(device_, &pool_info, nullptr, &pool));
  command_pool_ = UniqueHandle<VkCommandPool>(&vk_, device_, pool);
  set_debug_name(command_pool_, "carbtf submit-and-wait pool");

  auto allocate = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  allocate.commandPool = pool;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  CARBTF_VK_TRY(vk_.vkAllocateCommandBuffers(device_, &allocate, &command_buffer_));

  auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  VkFence fence = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk_.vkCreateFence(device_, &fence_info, nullptr, &fence));
  fence_ = UniqueHandle<VkFence>(&vk_, device_, fence);
  set_debug_name(fence_, "carbtf submit-and-wait fence");
  return {};
}

bool Context::find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                               std::uint32_t& index) const noexcept {
  VkPhysicalDeviceMemoryProperties properties{};
  vk_.vkGetPhysicalDeviceMemoryProperties(physical_device_, &properties);
  for (std::uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
    if ((type_bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & required) == required) {
      index = i;
      return true;
    }
  }
  return false;
}

void Context::set_debug_name(VkObjectType type, std::uint64_t handle, const char* name) const noexcept {
  if (!debug_utils_ || !vk_.vkSetDebugUtilsObjectNameEXT || handle == 0) return;
  auto info = vk_struct<VkDebugUtilsObjectNameInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT);
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name;
  vk_.vkSetDebugUtilsObjectNameEXT(device_, &info);
}

Status Context::submit_and_wait(const std::function<Status(VkCommandBuffer)>& record) noexcept {
  return guarded("submitting GPU work", [&]() -> Status {
    CARBTF_VK_TRY(vk_.vkResetCommandPool(device_, command_pool_.get(), 0));
    auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    CARBTF_VK_TRY(vk_.vkBeginCommandBuffer(command_buffer_, &begin));
    Status recorded = record(command_buffer_);
    // End even on failure, so the pool is left in a resettable state.
    const VkResult ended = vk_.vkEndCommandBuffer(command_buffer_);
    CARBTF_TRY(std::move(recorded));
    CARBTF_VK_TRY(ended);

    auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &command_buffer_;
    VkFence fence = fence_.get();
    CARBTF_VK_TRY(vk_.vkQueueSubmit(queue_, 1, &submit, fence));
    const VkResult waited = vk_.vkWaitForFences(device_, 1, &fence, VK_TRUE, kSubmitTimeoutNs);
    if (waited == VK_TIMEOUT) {
      vk_.vkDeviceWaitIdle(device_);
      return {ErrorCode::device_lost, "GPU work did not finish within 600 s"};
    }
    CARBTF_VK_TRY(waited);
    CARBTF_VK_TRY(vk_.vkResetFences(device_, 1, &fence));
    return {};
  });
}

ValidationReport Context::validation_report() const {
  ValidationReport report;
  if (!messenger_) return report;
  report.warnings = messenger_->warnings.load();
  report.errors = messenger_->errors.load();
  std::lock_guard<std::mutex> lock(messenger_->mutex);
  report.messages = messenger_->messages;
  return report;
}

Status enumerate_devices(std::vector<DeviceInfo>& out) noexcept {
  return guarded("listing Vulkan devices", [&]() -> Status {
    VulkanFunctions vk{};
    void* library = nullptr;
    CARBTF_TRY(detail::open_vulkan_loader(library, vk.vkGetInstanceProcAddr));
    struct Closer {
      void* library;
      ~Closer() { detail::close_vulkan_loader(library); }
    } closer{library};
    CARBTF_TRY(detail::load_global_functions(vk));
    auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "carbtf devices";
    app.apiVersion = VK_API_VERSION_1_2;
    auto create = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    create.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    const VkResult created = vk.vkCreateInstance(&create, nullptr, &instance);
    if (created == VK_ERROR_INCOMPATIBLE_DRIVER) return no_driver_status();
    CARBTF_VK_TRY(created);
    Status status = detail::load_instance_functions(vk, instance, false);
    if (status.ok()) {
      std::uint32_t count = 0;
      vk.vkEnumeratePhysicalDevices(instance, &count, nullptr);
      std::vector<VkPhysicalDevice> devices(count);
      vk.vkEnumeratePhysicalDevices(instance, &count, devices.data());
      out.clear();
      for (std::uint32_t i = 0; i < count; ++i)
        out.push_back(detail::describe_physical_device(vk, devices[i], i));
      if (count == 0) status = no_driver_status();
    }
    if (vk.vkDestroyInstance) vk.vkDestroyInstance(instance, nullptr);
    return status;
  });
}

}  // namespace carbtf
