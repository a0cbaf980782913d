#include "vulkan/compute_pipeline.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "vulkan/descriptor_writes.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf::detail {
namespace {

VkDescriptorType descriptor_type(BindingKind kind) {
  return kind == BindingKind::storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                            : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

}  // namespace

Status create_shader_module(const Context& context, const std::uint32_t* spirv, std::size_t bytes,
                            const char* debug_name, UniqueHandle<VkShaderModule>& out) {
  const VulkanFunctions& vk = context.vk();
  auto module_info = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  module_info.codeSize = bytes;
  module_info.pCode = spirv;
  VkShaderModule module_handle = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk.vkCreateShaderModule(context.device(), &module_info, nullptr, &module_handle));
  out = UniqueHandle<VkShaderModule>(&vk, context.device(), module_handle);
  context.set_debug_name(out, debug_name);
  return {};
}

Status ComputePipeline::create(const Context& context, const ComputePipelineInfo& info,
                               ComputePipeline& out) {
  const VulkanFunctions& vk = context.vk();
  const VkDevice device = context.device();
  if (info.binding_count == 0 || info.binding_count > kMaxBindings) {
    return {ErrorCode::invalid_argument, std::string(info.debug_name) + ": binding count out of range"};
  }
  out.binding_count = info.binding_count;
  std::copy(std::begin(info.bindings), std::end(info.bindings), std::begin(out.bindings));

  std::vector<VkDescriptorSetLayoutBinding> bindings(info.binding_count);
  for (std::uint32_t i = 0; i < info.binding_count; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = descriptor_type(info.bindings[i]);
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  auto set_info =
      vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  set_info.bindingCount = info.binding_count;
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk.vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout));
  out.set_layout = UniqueHandle<VkDescriptorSetLayout>(&vk, device, set_layout);
  context.set_debug_name(out.set_layout, info.debug_name);

  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, info.push_constant_bytes};
  auto layout_info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  layout_info.pushConstantRangeCount = info.push_constant_bytes > 0 ? 1 : 0;
  layout_info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk.vkCreatePipelineLayout(device, &layout_info, nullptr, &layout));
  out.layout = UniqueHandle<VkPipelineLayout>(&vk, device, layout);
  context.set_debug_name(out.layout, info.debug_name);

  UniqueHandle<VkShaderModule> shader_module;
  CARBTF_TRY(create_shader_module(context, info.spirv, info.spirv_bytes, info.debug_name, shader_module));

  auto pipeline_info = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = shader_module.get();
  pipeline_info.stage.pName = "main";
  pipeline_info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  CARBTF_VK_TRY(vk.vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline));
  out.pipeline = UniqueHandle<VkPipeline>(&vk, device, pipeline);
  context.set_debug_name(out.pipeline, info.debug_name);
  return {};
}

void ComputePipeline::bind(const Context& context, VkCommandBuffer command_buffer,
                           const BindingResource* resources, const void* push_constants,
                           std::uint32_t push_constant_bytes) const noexcept {
  const VulkanFunctions& vk = context.vk();
  vk.vkCmdBindPipeline(command_buffer, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
  std::array<VkWriteDescriptorSet, kMaxBindings> writes{};
  for (std::uint32_t i = 0; i < binding_count; ++i) {
    const bool image = bindings[i] == BindingKind::storage_image;
    writes[i] = descriptor_write(i, {.type = descriptor_type(bindings[i]),
                                     .buffer = image ? nullptr : &resources[i].buffer,
                                     .image = image ? &resources[i].image : nullptr});
  }
  vk.vkCmdPushDescriptorSetKHR(command_buffer, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, binding_count,
                               writes.data());
  if (push_constant_bytes > 0) {
    vk.vkCmdPushConstants(command_buffer, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes,
                          push_constants);
  }
}

}  // namespace carbtf::detail
