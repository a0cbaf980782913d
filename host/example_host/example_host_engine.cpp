#include "example_host/example_host_engine.hpp"

#include <cstring>
#include <functional>
#include <stdexcept>

#include <carbtf_host_spirv/host_mesh_fragment.h>
#include <carbtf_host_spirv/host_mesh_vertex.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace carbtf::example {

namespace {

void vk_check(VkResult result, const char* call) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(call) + " failed (VkResult " + std::to_string(result) + ")");
}
#define HOST_VK(call) vk_check((call), #call)

void carbtf_check(const Status& status, const char* what) {
  if (!status.ok()) throw std::runtime_error(std::string(what) + ": " + status.message());
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  static_cast<std::vector<std::string>*>(user)->emplace_back(data->pMessage);
  return VK_FALSE;
}

// The host's own per-frame uniforms (shaders/host_mesh.vert), std140.
struct HostFrameUniforms {
  float view_projection[16];
  float camera[4];
  float light[4];
};

struct HostBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
};

}  // namespace

struct ExampleHostEngine::Target {
  VkImage colour = VK_NULL_HANDLE, depth = VK_NULL_HANDLE;
  VkDeviceMemory colour_memory = VK_NULL_HANDLE, depth_memory = VK_NULL_HANDLE;
  VkImageView colour_view = VK_NULL_HANDLE, depth_view = VK_NULL_HANDLE;
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  HostBuffer readback, uniforms;
  VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet frame_set = VK_NULL_HANDLE;
};

namespace {

HostBuffer make_buffer(VkDevice device, VkPhysicalDevice physical, VkDeviceSize size,
                       VkBufferUsageFlags usage) {
  HostBuffer b;
  auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  info.size = size;
  info.usage = usage;
  HOST_VK(vkCreateBuffer(device, &info, nullptr, &b.buffer));
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, b.buffer, &requirements);
  VkPhysicalDeviceMemoryProperties properties;
  vkGetPhysicalDeviceMemoryProperties(physical, &properties);
  const VkMemoryPropertyFlags wanted =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  std::uint32_t type = 0;
  while (type < properties.memoryTypeCount &&
         !((requirements.memoryTypeBits & (1u << type)) &&
           (properties.memoryTypes[type].propertyFlags & wanted) == wanted)) {
    ++type;
  }
  if (type == properties.memoryTypeCount) throw std::runtime_error("no host-visible coherent memory");
  auto allocate = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = type;
  HOST_VK(vkAllocateMemory(device, &allocate, nullptr, &b.memory));
  HOST_VK(vkBindBufferMemory(device, b.buffer, b.memory, 0));
  HOST_VK(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  return b;
}

void destroy_buffer(VkDevice device, HostBuffer& b) {
  if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(device, b.memory, nullptr);
  b = {};
}

}  // namespace

ExampleHostEngine::ExampleHostEngine(std::uint32_t width, std::uint32_t height, bool validation)
    : width_(width), height_(height) {
  create_device(validation);
  create_target();
}

void ExampleHostEngine::create_device(bool validation) {
  auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "carbtf example host";
  app.apiVersion = VK_API_VERSION_1_2;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  auto create = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  create.pApplicationInfo = &app;
  create.enabledLayerCount = validation ? 1 : 0;
  create.ppEnabledLayerNames = &layer;
  create.enabledExtensionCount = 1;
  create.ppEnabledExtensionNames = &extension;
  HOST_VK(vkCreateInstance(&create, nullptr, &instance_));
  auto messenger_info =
      vk_struct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
  messenger_info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType =
      VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  messenger_info.pfnUserCallback = on_message;
  messenger_info.pUserData = &messages_;
  auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
  HOST_VK(create_messenger(instance_, &messenger_info, nullptr, &messenger_));

  std::uint32_t count = 0;
  HOST_VK(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
  if (count == 0) throw std::runtime_error("no Vulkan device");
  std::vector<VkPhysicalDevice> devices(count);
  HOST_VK(vkEnumeratePhysicalDevices(instance_, &count, devices.data()));
  physical_device_ = devices[0];
  std::uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &families, nullptr);
  std::vector<VkQueueFamilyProperties> properties(families);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &families, properties.data());
  const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  while (family_ < families && (properties[family_].queueFlags & wanted) != wanted) ++family_;
  if (family_ == families) throw std::runtime_error("no graphics and compute queue family");

  const float priority = 1.0f;
  auto queue_info = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  queue_info.queueFamilyIndex = family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  // carbtf names the extensions it needs; the host enables them on its own device.
  const std::vector<const char*>& extensions = required_device_extensions();
  auto device_info = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  device_info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  device_info.ppEnabledExtensionNames = extensions.data();
  HOST_VK(vkCreateDevice(physical_device_, &device_info, nullptr, &device_));
  vkGetDeviceQueue(device_, family_, 0, &queue_);

  auto pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = family_;
  HOST_VK(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_));
  auto allocate = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  allocate.commandPool = pool_;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  HOST_VK(vkAllocateCommandBuffers(device_, &allocate, &command_buffer_));
  auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  HOST_VK(vkCreateFence(device_, &fence_info, nullptr, &fence_));
}

std::uint32_t ExampleHostEngine::memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties properties;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &properties);
  for (std::uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & flags) == flags) return i;
  }
  throw std::runtime_error("no suitable memory type");
}

void ExampleHostEngine::create_target() {
  target_ = std::make_unique<Target>();
  Target& t = *target_;
  auto image = [&](VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, VkImage& handle,
                   VkDeviceMemory& memory, VkImageView& view) {
    auto info = vk_struct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width_, height_, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.usage = usage;
    HOST_VK(vkCreateImage(device_, &info, nullptr, &handle));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device_, handle, &requirements);
    auto allocate = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex = memory_type(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    HOST_VK(vkAllocateMemory(device_, &allocate, nullptr, &memory));
    HOST_VK(vkBindImageMemory(device_, handle, memory, 0));
    auto view_info = vk_struct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    view_info.image = handle;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = format;
    view_info.subresourceRange = {aspect, 0, 1, 0, 1};
    HOST_VK(vkCreateImageView(device_, &view_info, nullptr, &view));
  };
  image(VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
        VK_IMAGE_ASPECT_COLOR_BIT, t.colour, t.colour_memory, t.colour_view);
  image(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, t.depth,
        t.depth_memory, t.depth_view);

  VkAttachmentDescription attachments[2]{};
  attachments[0].format = VK_FORMAT_R32G32B32A32_SFLOAT;
  attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
  attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  attachments[1] = attachments[0];
  attachments[1].format = VK_FORMAT_D32_SFLOAT;
  attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  const VkAttachmentReference colour_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colour_ref;
  subpass.pDepthStencilAttachment = &depth_ref;
  VkSubpassDependency dependencies[2]{};
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  dependencies[0].dstStageMask =
      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                                  VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                  VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  auto pass_info = vk_struct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
  pass_info.attachmentCount = 2;
  pass_info.pAttachments = attachments;
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = 2;
  pass_info.pDependencies = dependencies;
  HOST_VK(vkCreateRenderPass(device_, &pass_info, nullptr, &t.render_pass));
  const VkImageView views[2] = {t.colour_view, t.depth_view};
  auto framebuffer_info = vk_struct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
  framebuffer_info.renderPass = t.render_pass;
  framebuffer_info.attachmentCount = 2;
  framebuffer_info.pAttachments = views;
  framebuffer_info.width = width_;
  framebuffer_info.height = height_;
  framebuffer_info.layers = 1;
  HOST_VK(vkCreateFramebuffer(device_, &framebuffer_info, nullptr, &t.framebuffer));

  t.readback = make_buffer(device_, physical_device_, VkDeviceSize{width_} * height_ * 16,
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  t.uniforms =
      make_buffer(device_, physical_device_, sizeof(HostFrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                             VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                             nullptr};
  auto layout_info =
      vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  layout_info.bindingCount = 1;
  layout_info.pBindings = &binding;
  HOST_VK(vkCreateDescriptorSetLayout(device_, &layout_info, nullptr, &t.frame_layout));
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
  auto pool_info = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &size;
  HOST_VK(vkCreateDescriptorPool(device_, &pool_info, nullptr, &t.pool));
  auto allocate = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  allocate.descriptorPool = t.pool;
  allocate.descriptorSetCount = 1;
  allocate.pSetLayouts = &t.frame_layout;
  HOST_VK(vkAllocateDescriptorSets(device_, &allocate, &t.frame_set));
  const VkDescriptorBufferInfo buffer_info{t.uniforms.buffer, 0, sizeof(HostFrameUniforms)};
  auto write = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
  write.dstSet = t.frame_set;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  write.pBufferInfo = &buffer_info;
  vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
}

void ExampleHostEngine::create_pipeline() {
  auto module = [&](const std::uint32_t* code, std::size_t bytes) {
    auto info = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule m = VK_NULL_HANDLE;
    HOST_VK(vkCreateShaderModule(device_, &info, nullptr, &m));
    return m;
  };
  const VkShaderModule vertex =
      module(carbtf_host_spirv_host_mesh_vertex, sizeof(carbtf_host_spirv_host_mesh_vertex));
  const VkShaderModule fragment =
      module(carbtf_host_spirv_host_mesh_fragment, sizeof(carbtf_host_spirv_host_mesh_fragment));

  // The host's layout: its own frame set at 0, carbtf's material set at 1 (CARBTF_MATERIAL_SET in the
  // shader).
  const VkDescriptorSetLayout sets[2] = {target_->frame_layout, binding_->set_layout()};
  auto layout_info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  layout_info.setLayoutCount = 2;
  layout_info.pSetLayouts = sets;
  HOST_VK(vkCreatePipelineLayout(device_, &layout_info, nullptr, &pipeline_layout_));

  VkPipelineShaderStageCreateInfo stages[2];
  for (auto& stage : stages) {
    stage = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    stage.pName = "main";
  }
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex;
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment;
  // carbtf_material.glsl's specialization constants, as the binding says: the relief's cast shadows
  // compiled out where the material has none, and the sampler's filtering where the binding's filters.
  MaterialShaderConstants constants;
  binding_->shader_constants(constants);
  stages[1].pSpecializationInfo = &constants.info;
  const VkVertexInputBindingDescription vertex_binding{0, sizeof(MeshVertex), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attributes[4] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, normal)},
      {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(MeshVertex, tangent)},
      {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(MeshVertex, uv)}};
  auto input = vk_struct<VkPipelineVertexInputStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &vertex_binding;
  input.vertexAttributeDescriptionCount = 4;
  input.pVertexAttributeDescriptions = attributes;
  auto assembly = vk_struct<VkPipelineInputAssemblyStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  const VkViewport viewport{0, 0, static_cast<float>(width_), static_cast<float>(height_), 0, 1};
  const VkRect2D scissor{{0, 0}, {width_, height_}};
  auto viewport_state =
      vk_struct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
  viewport_state.viewportCount = viewport_state.scissorCount = 1;
  viewport_state.pViewports = &viewport;
  viewport_state.pScissors = &scissor;
  auto raster = vk_struct<VkPipelineRasterizationStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  auto multisample = vk_struct<VkPipelineMultisampleStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  auto depth = vk_struct<VkPipelineDepthStencilStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
  depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blend_attachment{};
  blend_attachment.colorWriteMask = 0xF;
  auto blend = vk_struct<VkPipelineColorBlendStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
  blend.attachmentCount = 1;
  blend.pAttachments = &blend_attachment;
  auto info = vk_struct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport_state;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.layout = pipeline_layout_;
  info.renderPass = target_->render_pass;
  const VkResult result = vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
  vkDestroyShaderModule(device_, vertex, nullptr);
  vkDestroyShaderModule(device_, fragment, nullptr);
  vk_check(result, "vkCreateGraphicsPipelines");
}

void ExampleHostEngine::submit(const std::function<void(VkCommandBuffer)>& record) {
  HOST_VK(vkResetCommandBuffer(command_buffer_, 0));
  auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  HOST_VK(vkBeginCommandBuffer(command_buffer_, &begin));
  record(command_buffer_);
  HOST_VK(vkEndCommandBuffer(command_buffer_));
  auto submit_info = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  submit_info.commandBufferCount = 1;
  submit_info.pCommandBuffers = &command_buffer_;
  HOST_VK(vkResetFences(device_, 1, &fence_));
  HOST_VK(vkQueueSubmit(queue_, 1, &submit_info, fence_));
  HOST_VK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
}

AdoptInfo ExampleHostEngine::adopt_info() const {
  AdoptInfo info;
  info.instance = instance_;
  info.physical_device = physical_device_;
  info.device = device_;
  info.queue_family_index = family_;
  info.queue = queue_;
  info.get_instance_proc_addr = vkGetInstanceProcAddr;
  info.debug_utils_enabled = true;
  return info;
}

void ExampleHostEngine::load_material(const Material& material, std::uint32_t texture_size,
                                      std::uint64_t seed) {
  unload_material();
  carbtf_check(Context::adopt(adopt_info(), context_), "carbtf cannot adopt the host's device");
  carbtf_check(SubspaceSynthesizer::create(*context_, synthesizer_), "cannot create the synthesizer");
  SynthesisRequest request;
  request.seed = seed;
  request.width = request.height = texture_size;
  request.mip_levels = 0;  // all: the render pass samples them
  carbtf_check(synthesizer_->prepare(material, request), "cannot plan the synthesis");
  MaterialBindingInfo binding_info;
  binding_info.seed = seed;
  carbtf_check(MaterialBinding::create(*context_, material, material_textures(*synthesizer_, material),
                                       binding_info, binding_),
               "cannot bind the material");
  // carbtf records into the host's command buffer; the host submits when it likes.
  Status recorded, uploaded;
  submit([&](VkCommandBuffer cb) {
    recorded = synthesizer_->record(cb);
    uploaded = binding_->record_upload(cb);
  });
  carbtf_check(recorded, "cannot record the synthesis");
  carbtf_check(uploaded, "cannot record the material's upload");
  create_pipeline();
}

std::vector<float> ExampleHostEngine::draw(const Mesh& mesh, const HostView& view) {
  if (!binding_) throw std::runtime_error("draw() before load_material()");
  Target& t = *target_;
  HostBuffer vertices = make_buffer(device_, physical_device_, mesh.vertices.size() * sizeof(MeshVertex),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  std::memcpy(vertices.mapped, mesh.vertices.data(), mesh.vertices.size() * sizeof(MeshVertex));
  HostBuffer indices =
      make_buffer(device_, physical_device_, mesh.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(indices.mapped, mesh.indices.data(), mesh.indices.size() * 4);

  // The host's own camera maths (glm), Vulkan clip space.
  const glm::vec3 eye(view.eye[0], view.eye[1], view.eye[2]);
  glm::mat4 projection =
      glm::perspectiveRH_ZO(glm::radians(40.0f), static_cast<float>(width_) / height_, 0.05f, 100.0f);
  projection[1][1] = -projection[1][1];
  const glm::mat4 view_projection = projection * glm::lookAtRH(eye, glm::vec3(0), glm::vec3(0, 0, 1));
  HostFrameUniforms frame{};
  std::memcpy(frame.view_projection, glm::value_ptr(view_projection), sizeof frame.view_projection);
  const glm::vec3 light = glm::normalize(glm::vec3(view.light[0], view.light[1], view.light[2]));
  frame.camera[0] = eye.x, frame.camera[1] = eye.y, frame.camera[2] = eye.z, frame.camera[3] = 1;
  frame.light[0] = light.x, frame.light[1] = light.y, frame.light[2] = light.z;
  std::memcpy(t.uniforms.mapped, &frame, sizeof frame);

  submit([&](VkCommandBuffer cb) {
    VkClearValue clears[2]{};
    clears[1].depthStencil = {1.0f, 0};
    auto begin = vk_struct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    begin.renderPass = t.render_pass;
    begin.framebuffer = t.framebuffer;
    begin.renderArea = {{0, 0}, {width_, height_}};
    begin.clearValueCount = 2;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cb, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    const VkDescriptorSet sets[2] = {t.frame_set, binding_->set()};
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, 0, 2, sets, 0, nullptr);
    const VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cb, 0, 1, &vertices.buffer, &zero);
    vkCmdBindIndexBuffer(cb, indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cb, static_cast<std::uint32_t>(mesh.indices.size()), 1, 0, 0, 0);
    vkCmdEndRenderPass(cb);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(cb, t.colour, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.readback.buffer, 1, &copy);
    auto to_host = vk_struct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = t.readback.buffer;
    to_host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1,
                         &to_host, 0, nullptr);
  });
  std::vector<float> pixels(std::size_t{width_} * height_ * 4);
  std::memcpy(pixels.data(), t.readback.mapped, pixels.size() * sizeof(float));
  destroy_buffer(device_, vertices);
  destroy_buffer(device_, indices);
  return pixels;
}

void ExampleHostEngine::unload_material() {
  if (device_) vkDeviceWaitIdle(device_);
  if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
  if (pipeline_layout_) vkDestroyPipelineLayout(device_, pipeline_layout_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  pipeline_layout_ = VK_NULL_HANDLE;
  binding_.reset();
  synthesizer_.reset();
  context_.reset();
}

bool ExampleHostEngine::device_alive() {
  try {
    submit([](VkCommandBuffer) {});
    return true;
  } catch (const std::runtime_error&) {
    return false;
  }
}

ExampleHostEngine::~ExampleHostEngine() {
  unload_material();
  if (target_) {
    Target& t = *target_;
    vkDestroyDescriptorPool(device_, t.pool, nullptr);
    vkDestroyDescriptorSetLayout(device_, t.frame_layout, nullptr);
    destroy_buffer(device_, t.readback);
    destroy_buffer(device_, t.uniforms);
    vkDestroyFramebuffer(device_, t.framebuffer, nullptr);
    vkDestroyRenderPass(device_, t.render_pass, nullptr);
    vkDestroyImageView(device_, t.colour_view, nullptr);
    vkDestroyImageView(device_, t.depth_view, nullptr);
    vkDestroyImage(device_, t.colour, nullptr);
    vkDestroyImage(device_, t.depth, nullptr);
    vkFreeMemory(device_, t.colour_memory, nullptr);
    vkFreeMemory(device_, t.depth_memory, nullptr);
  }
  if (fence_) vkDestroyFence(device_, fence_, nullptr);
  if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
  if (device_) vkDestroyDevice(device_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

}  // namespace carbtf::example
