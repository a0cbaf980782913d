#include "carbtf/engine/render/mesh_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include <carbtf_gpu_shared.h>
#include <carbtf_spirv/material_fragment.h>
#include <carbtf_spirv/material_vertex.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "vulkan/barriers.hpp"
#include "vulkan/compute_pipeline.hpp"
#include "vulkan/descriptor_writes.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {

static_assert(kMaxRenderLights == gpu::CARBTF_RENDER_MAX_LIGHTS);

namespace {

glm::vec3 vec3_of(const std::array<float, 3>& a) {
  return {a[0], a[1], a[2]};
}

std::uint32_t bytes_per_pixel(VkFormat format) {
  return format == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 4;
}

}  // namespace

struct MeshRenderer::Resources {
  const MaterialBinding* binding = nullptr;
  RenderTargetInfo target;
  Image colour;
  Image depth;
  Buffer readback;
  Buffer uniforms;
  Buffer vertices;
  Buffer indices;
  std::uint32_t index_count = 0;
  UniqueHandle<VkRenderPass> render_pass;
  UniqueHandle<VkFramebuffer> framebuffer;
  UniqueHandle<VkDescriptorSetLayout> frame_layout;
  UniqueHandle<VkPipelineLayout> layout;
  UniqueHandle<VkPipeline> pipeline;
};

namespace {

Status create_render_pass(const Context& context, VkFormat colour_format, UniqueHandle<VkRenderPass>& out) {
  VkAttachmentDescription attachments[2]{};
  attachments[0].format = colour_format;
  attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
  attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
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
  // Earlier use of the attachments (a previous frame's copy, depth tests) before this frame's writes.
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].dstSubpass = 0;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  dependencies[0].dstStageMask =
      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                                  VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                  VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  // The colour target's copy to the readback buffer.
  dependencies[1].srcSubpass = 0;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  auto info = vk_struct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
  info.attachmentCount = 2;
  info.pAttachments = attachments;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = dependencies;
  VkRenderPass pass = VK_NULL_HANDLE;
  CARBTF_VK_TRY(context.vk().vkCreateRenderPass(context.device(), &info, nullptr, &pass));
  out = UniqueHandle<VkRenderPass>(&context.vk(), context.device(), pass);
  context.set_debug_name(out, "carbtf mesh render pass");
  return {};
}

Status create_pipeline(const Context& context, VkRenderPass render_pass, VkPipelineLayout layout,
                       const MaterialBinding& binding, UniqueHandle<VkPipeline>& out) {
  UniqueHandle<VkShaderModule> vertex, fragment;
  CARBTF_TRY(detail::create_shader_module(context, carbtf_spirv_material_vertex,
                                          sizeof(carbtf_spirv_material_vertex), "carbtf material vertex",
                                          vertex));
  CARBTF_TRY(detail::create_shader_module(context, carbtf_spirv_material_fragment,
                                          sizeof(carbtf_spirv_material_fragment), "carbtf material fragment",
                                          fragment));
  VkPipelineShaderStageCreateInfo stages[2];
  for (auto& stage : stages) {
    stage = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    stage.pName = "main";
  }
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex.get();
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment.get();
  // carbtf_material.glsl's constants: the shadows compiled out for a material without cast shadows, and
  // the textures read through the sampler where the binding's filters.
  MaterialShaderConstants constants;
  binding.shader_constants(constants);
  stages[1].pSpecializationInfo = &constants.info;

  const VkVertexInputBindingDescription vertex_binding{0, sizeof(MeshVertex), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attributes[4] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, normal)},
      {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(MeshVertex, tangent)},
      {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(MeshVertex, uv)}};
  auto vertex_input = vk_struct<VkPipelineVertexInputStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
  vertex_input.vertexBindingDescriptionCount = 1;
  vertex_input.pVertexBindingDescriptions = &vertex_binding;
  vertex_input.vertexAttributeDescriptionCount = 4;
  vertex_input.pVertexAttributeDescriptions = attributes;
  auto assembly = vk_struct<VkPipelineInputAssemblyStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  auto viewport =
      vk_struct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  auto raster = vk_struct<VkPipelineRasterizationStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;  // the depth test hides back faces; open meshes show both sides
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  auto multisample = vk_struct<VkPipelineMultisampleStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  auto depth = vk_struct<VkPipelineDepthStencilStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
  depth.depthTestEnable = VK_TRUE;
  depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blend_attachment{};
  blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                    VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  auto blend = vk_struct<VkPipelineColorBlendStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
  blend.attachmentCount = 1;
  blend.pAttachments = &blend_attachment;
  const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  auto dynamic =
      vk_struct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;

  auto info = vk_struct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  info.renderPass = render_pass;
  VkPipeline pipeline = VK_NULL_HANDLE;
  CARBTF_VK_TRY(
      context.vk().vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  out = UniqueHandle<VkPipeline>(&context.vk(), context.device(), pipeline);
  context.set_debug_name(out, "carbtf mesh pipeline");
  return {};
}

}  // namespace

Status MeshRenderer::create(Context& context, const MaterialBinding& binding, const RenderTargetInfo& target,
                            std::unique_ptr<MeshRenderer>& out) noexcept {
  try {
    if (target.colour_format != VK_FORMAT_R8G8B8A8_SRGB &&
        target.colour_format != VK_FORMAT_R32G32B32A32_SFLOAT) {
      return {ErrorCode::invalid_argument,
              "the render target format must be R8G8B8A8_SRGB or R32G32B32A32_SFLOAT"};
    }
    const std::uint32_t limit = context.device_info().max_image_dimension_2d;
    if (target.width == 0 || target.height == 0 || target.width > limit || target.height > limit) {
      return {ErrorCode::invalid_argument, "the render target " + std::to_string(target.width) + "x" +
                                               std::to_string(target.height) + " is outside 1.." +
                                               std::to_string(limit) + " on this device"};
    }
    std::unique_ptr<MeshRenderer> renderer(new MeshRenderer());
    renderer->context_ = &context;
    renderer->resources_ = std::make_unique<Resources>();
    Resources& r = *renderer->resources_;
    r.binding = &binding;
    r.target = target;
    const VulkanFunctions& vk = context.vk();
    const VkDevice device = context.device();

    ImageCreateInfo colour_info;
    colour_info.width = target.width;
    colour_info.height = target.height;
    colour_info.format = target.colour_format;
    colour_info.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    colour_info.debug_name = "carbtf render colour";
    CARBTF_TRY(Image::create(context, colour_info, r.colour));
    ImageCreateInfo depth_info = colour_info;
    depth_info.format = VK_FORMAT_D32_SFLOAT;
    depth_info.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    depth_info.debug_name = "carbtf render depth";
    CARBTF_TRY(Image::create(context, depth_info, r.depth));
    CARBTF_TRY(Buffer::create(
        context,
        {VkDeviceSize{target.width} * target.height * bytes_per_pixel(target.colour_format),
         VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::host_readback, "carbtf render readback"},
        r.readback));
    CARBTF_TRY(Buffer::create(context,
                              {sizeof(gpu::RenderFrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                               MemoryUsage::host_upload, "carbtf render frame uniforms"},
                              r.uniforms));

    CARBTF_TRY(create_render_pass(context, target.colour_format, r.render_pass));
    const VkImageView views[2] = {r.colour.view(), r.depth.view()};
    auto framebuffer_info = vk_struct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
    framebuffer_info.renderPass = r.render_pass.get();
    framebuffer_info.attachmentCount = 2;
    framebuffer_info.pAttachments = views;
    framebuffer_info.width = target.width;
    framebuffer_info.height = target.height;
    framebuffer_info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreateFramebuffer(device, &framebuffer_info, nullptr, &framebuffer));
    r.framebuffer = UniqueHandle<VkFramebuffer>(&vk, device, framebuffer);
    context.set_debug_name(r.framebuffer, "carbtf render framebuffer");

    const VkDescriptorSetLayoutBinding frame_binding{
        0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
        nullptr};
    auto frame_layout_info =
        vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    frame_layout_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    frame_layout_info.bindingCount = 1;
    frame_layout_info.pBindings = &frame_binding;
    VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreateDescriptorSetLayout(device, &frame_layout_info, nullptr, &frame_layout));
    r.frame_layout = UniqueHandle<VkDescriptorSetLayout>(&vk, device, frame_layout);
    const VkDescriptorSetLayout set_layouts[2] = {binding.set_layout(), frame_layout};
    auto layout_info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    layout_info.setLayoutCount = 2;
    layout_info.pSetLayouts = set_layouts;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreatePipelineLayout(device, &layout_info, nullptr, &layout));
    r.layout = UniqueHandle<VkPipelineLayout>(&vk, device, layout);
    context.set_debug_name(r.layout, "carbtf mesh pipeline layout");
    CARBTF_TRY(create_pipeline(context, r.render_pass.get(), layout, binding, r.pipeline));
    out = std::move(renderer);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while creating the mesh renderer"};
  }
}

MeshRenderer::~MeshRenderer() = default;

const RenderTargetInfo& MeshRenderer::target() const noexcept {
  return resources_->target;
}

Status MeshRenderer::set_mesh(const Mesh& mesh) noexcept {
  CARBTF_TRY(validate_mesh(mesh));
  Resources& r = *resources_;
  CARBTF_TRY(Buffer::create(*context_,
                            {mesh.vertices.size() * sizeof(MeshVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                             MemoryUsage::host_upload, "carbtf mesh vertices"},
                            r.vertices));
  std::memcpy(r.vertices.mapped(), mesh.vertices.data(), mesh.vertices.size() * sizeof(MeshVertex));
  CARBTF_TRY(Buffer::create(*context_,
                            {mesh.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                             MemoryUsage::host_upload, "carbtf mesh indices"},
                            r.indices));
  std::memcpy(r.indices.mapped(), mesh.indices.data(), mesh.indices.size() * 4);
  r.index_count = static_cast<std::uint32_t>(mesh.indices.size());
  return {};
}

Status MeshRenderer::record(VkCommandBuffer cb, const RenderScene& scene) noexcept {
  Resources& r = *resources_;
  if (r.index_count == 0) return {ErrorCode::invalid_argument, "no mesh: call set_mesh() before record()"};
  CARBTF_TRY(check_render_lights(scene));
  const VulkanFunctions& vk = context_->vk();
  const float aspect = static_cast<float>(r.target.width) / static_cast<float>(r.target.height);

  gpu::RenderFrameUniforms frame{};
  const std::array<float, 16> vp = view_projection(scene.camera, aspect);
  std::copy(vp.begin(), vp.end(), frame.view_projection.columns);
  std::copy(scene.model.begin(), scene.model.end(), frame.model.columns);
  const auto& c = scene.camera;
  if (c.fov_y_degrees > 0.0f) {
    frame.camera = {c.eye[0], c.eye[1], c.eye[2], 1.0f};
  } else {
    const glm::vec3 towards = glm::normalize(vec3_of(c.eye) - vec3_of(c.target));
    frame.camera = {towards.x, towards.y, towards.z, 0.0f};
  }
  const auto lights = static_cast<std::uint32_t>(scene.lights.size());  // checked above
  for (std::uint32_t i = 0; i < lights; ++i) {
    const RenderLight& light = scene.lights[i];
    glm::vec3 p = vec3_of(light.position);
    if (!light.point) p = glm::normalize(p);
    frame.light_position[i] = {p.x, p.y, p.z, light.point ? 1.0f : 0.0f};
    frame.light_colour[i] = {light.colour[0], light.colour[1], light.colour[2], 0.0f};
  }
  frame.counts.x = lights;
  std::memcpy(r.uniforms.mapped(), &frame, sizeof frame);

  VkClearValue clears[2]{};
  for (int k = 0; k < 4; ++k) clears[0].color.float32[k] = r.target.clear[k];
  clears[1].depthStencil = {1.0f, 0};
  auto begin = vk_struct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
  begin.renderPass = r.render_pass.get();
  begin.framebuffer = r.framebuffer.get();
  begin.renderArea = {{0, 0}, {r.target.width, r.target.height}};
  begin.clearValueCount = 2;
  begin.pClearValues = clears;
  vk.vkCmdBeginRenderPass(cb, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vk.vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipeline.get());
  const VkViewport viewport{0, 0, static_cast<float>(r.target.width), static_cast<float>(r.target.height),
                            0, 1};
  const VkRect2D scissor{{0, 0}, {r.target.width, r.target.height}};
  vk.vkCmdSetViewport(cb, 0, 1, &viewport);
  vk.vkCmdSetScissor(cb, 0, 1, &scissor);
  const VkDescriptorSet material_set = r.binding->set();
  vk.vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout.get(), 0, 1, &material_set, 0,
                             nullptr);
  const VkDescriptorBufferInfo uniform_info{r.uniforms.handle(), 0, sizeof(gpu::RenderFrameUniforms)};
  const VkWriteDescriptorSet write =
      detail::descriptor_write(0, {.type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, .buffer = &uniform_info});
  vk.vkCmdPushDescriptorSetKHR(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout.get(), 1, 1, &write);
  const VkDeviceSize zero = 0;
  const VkBuffer vertex_buffer = r.vertices.handle();
  vk.vkCmdBindVertexBuffers(cb, 0, 1, &vertex_buffer, &zero);
  vk.vkCmdBindIndexBuffer(cb, r.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
  vk.vkCmdDrawIndexed(cb, r.index_count, 1, 0, 0, 0);
  vk.vkCmdEndRenderPass(cb);

  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {r.target.width, r.target.height, 1};
  vk.vkCmdCopyImageToBuffer(cb, r.colour.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.readback.handle(),
                            1, &copy);
  detail::memory_barrier(vk, cb, {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT},
                         {VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT});
  return {};
}

Status MeshRenderer::read_back(RenderedImage& out) const noexcept {
  try {
    const Resources& r = *resources_;
    CARBTF_TRY(r.readback.invalidate_for_host_read());
    out.width = r.target.width;
    out.height = r.target.height;
    out.format = r.target.colour_format;
    const auto* bytes = static_cast<const std::uint8_t*>(r.readback.mapped());
    out.bytes.assign(bytes, bytes + r.readback.size());
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while reading the frame back"};
  }
}

Status MeshRenderer::render(const RenderScene& scene, RenderedImage& out) noexcept {
  CARBTF_TRY(context_->submit_and_wait([&](VkCommandBuffer cb) { return record(cb, scene); }));
  return read_back(out);
}

}  // namespace carbtf
