// Embedding: a host engine creates its own instance and device; carbtf adopts them, runs a dispatch,
// is destroyed, and the host's handles are still valid. The host's validation messenger sees every
// message, including leaks reported when the host finally destroys its device.
#include <catch2/catch.hpp>

#include <vulkan/vulkan.h>

#include <atomic>
#include <string>
#include <vector>

#include "carbtf/engine/synthesis/noise_generator.hpp"
#include "carbtf/reference/noise.hpp"
#include "test_support.hpp"

using namespace carbtf;

namespace {

struct HostMessages {
  std::atomic<int> count{0};
  std::vector<std::string> texts;
};

VKAPI_ATTR VkBool32 VKAPI_CALL host_callback(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* messages = static_cast<HostMessages*>(user);
  messages->count++;
  messages->texts.emplace_back(data->pMessage);
  return VK_FALSE;
}

// A minimal host engine, written against the system loader the ordinary way (linked prototypes).
struct HostEngine {
  HostMessages messages;
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger = nullptr;

  HostEngine() {
    auto messenger_info = vk_struct<VkDebugUtilsMessengerCreateInfoEXT>(
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messenger_info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType =
        VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger_info.pfnUserCallback = host_callback;
    messenger_info.pUserData = &messages;

    auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.apiVersion = VK_API_VERSION_1_2;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    auto create = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    create.pApplicationInfo = &app;
    create.enabledLayerCount = 1;
    create.ppEnabledLayerNames = &layer;
    create.enabledExtensionCount = 1;
    create.ppEnabledExtensionNames = &extension;
    REQUIRE(vkCreateInstance(&create, nullptr, &instance) == VK_SUCCESS);
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    REQUIRE(create_messenger(instance, &messenger_info, nullptr, &messenger) == VK_SUCCESS);

    std::uint32_t count = 1;
    REQUIRE(vkEnumeratePhysicalDevices(instance, &count, &physical_device) != VK_ERROR_INITIALIZATION_FAILED);
    REQUIRE(count == 1);
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &families, nullptr);
    std::vector<VkQueueFamilyProperties> properties(families);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &families, properties.data());
    while (!(properties[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;

    const float priority = 1.0f;
    auto queue_info = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    auto device_info = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.enabledExtensionCount = static_cast<std::uint32_t>(required_device_extensions().size());
    device_info.ppEnabledExtensionNames = required_device_extensions().data();
    REQUIRE(vkCreateDevice(physical_device, &device_info, nullptr, &device) == VK_SUCCESS);
    vkGetDeviceQueue(device, family, 0, &queue);
  }

  // Proves the device and queue still work: create a buffer, submit a command buffer, wait on a fence.
  void use_handles() const {
    auto buffer_info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    buffer_info.size = 1024;
    buffer_info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    REQUIRE(vkCreateBuffer(device, &buffer_info, nullptr, &buffer) == VK_SUCCESS);
    vkDestroyBuffer(device, buffer, nullptr);

    auto pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool_info.queueFamilyIndex = family;
    VkCommandPool pool = VK_NULL_HANDLE;
    REQUIRE(vkCreateCommandPool(device, &pool_info, nullptr, &pool) == VK_SUCCESS);
    auto allocate = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    allocate.commandPool = pool;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    REQUIRE(vkAllocateCommandBuffers(device, &allocate, &cmd) == VK_SUCCESS);
    auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    REQUIRE(vkBeginCommandBuffer(cmd, &begin) == VK_SUCCESS);
    REQUIRE(vkEndCommandBuffer(cmd) == VK_SUCCESS);
    auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    VkFence fence = VK_NULL_HANDLE;
    REQUIRE(vkCreateFence(device, &fence_info, nullptr, &fence) == VK_SUCCESS);
    auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    REQUIRE(vkQueueSubmit(queue, 1, &submit, fence) == VK_SUCCESS);
    REQUIRE(vkWaitForFences(device, 1, &fence, VK_TRUE, 10'000'000'000ull) == VK_SUCCESS);
    vkDestroyFence(device, fence, nullptr);
    vkDestroyCommandPool(device, pool, nullptr);
  }

  ~HostEngine() {
    if (device) vkDestroyDevice(device, nullptr);
    if (messenger) destroy_messenger(instance, messenger, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
  }
};

}  // namespace

TEST_CASE("the engine adopts a host's device, dispatches, and leaves the host's handles alive",
          "[engine][embedding][validation]") {
  const bool host_gives_loader = GENERATE(true, false);
  INFO("host passes vkGetInstanceProcAddr: " << host_gives_loader);
  auto host = std::make_unique<HostEngine>();
  {
    AdoptInfo adopt;
    adopt.instance = host->instance;
    adopt.physical_device = host->physical_device;
    adopt.device = host->device;
    adopt.queue_family_index = host->family;
    adopt.queue = host->queue;
    adopt.get_instance_proc_addr = host_gives_loader ? &vkGetInstanceProcAddr : nullptr;
    adopt.debug_utils_enabled = true;
    std::unique_ptr<Context> context;
    const Status status = Context::adopt(adopt, context);
    INFO(status.message());
    REQUIRE(status.ok());
    CHECK_FALSE(context->owns_device());
    CHECK(context->device() == host->device);

    std::unique_ptr<NoiseGenerator> generator;
    REQUIRE(NoiseGenerator::create(*context, generator).ok());
    const NoiseBlock block{21, 4, 0, 0, 128, 96};
    std::vector<float> gpu, cpu(std::size_t{block.width} * block.height);
    REQUIRE(generator->generate(block, gpu).ok());
    reference::fill_noise_block(block.seed, block.field_id, 0, 0, block.width, block.height, cpu);
    test::require_bitwise_equal(gpu, cpu, block.width);
  }  // generator, then context, destroyed here

  host->use_handles();
  REQUIRE(vkDeviceWaitIdle(host->device) == VK_SUCCESS);
  vkDestroyDevice(host->device, nullptr);  // validation reports any object carbtf leaked on it
  host->device = VK_NULL_HANDLE;
  std::string all;
  for (const std::string& m : host->messages.texts) all += m + "\n";
  INFO("host validation messages:\n" << all);
  CHECK(host->messages.count == 0);
}

TEST_CASE("adoption rejects missing handles and a queue family without compute", "[engine][embedding]") {
  std::unique_ptr<Context> context;
  AdoptInfo empty;
  const Status status = Context::adopt(empty, context);
  CHECK(status.code() == ErrorCode::invalid_argument);
  CHECK(context == nullptr);

  auto host = std::make_unique<HostEngine>();
  AdoptInfo adopt;
  adopt.instance = host->instance;
  adopt.physical_device = host->physical_device;
  adopt.device = host->device;
  adopt.queue_family_index = 1000;
  adopt.queue = host->queue;
  const Status bad_family = Context::adopt(adopt, context);
  CHECK(bad_family.code() == ErrorCode::invalid_argument);
  CHECK_THAT(bad_family.message(), Catch::Contains("1000"));
  CHECK(host->messages.count == 0);
}
