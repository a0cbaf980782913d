// Internal: a compute pipeline from embedded SPIR-V, with one push-descriptor set (storage buffers
// and storage images) and a push-constant block. Every carbtf kernel is built this way, so that recording
// into a host's command buffer needs no descriptor pool.
#pragma once

#include <cstddef>
#include <cstdint>

#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf::detail {

// Bindings one carbtf kernel may have; recording uses a fixed array, no allocation.
inline constexpr std::uint32_t kMaxBindings = 8;

// What one binding is: a storage buffer, or a storage image in VK_IMAGE_LAYOUT_GENERAL.
enum class BindingKind : std::uint8_t { storage_buffer, storage_image };

// The resource pushed to one binding; `image` is used for storage images, `buffer` otherwise.
struct BindingResource {
  VkDescriptorBufferInfo buffer{};
  VkDescriptorImageInfo image{};
  static BindingResource of(VkBuffer handle, VkDeviceSize offset, VkDeviceSize range) {
    BindingResource resource;
    resource.buffer = {handle, offset, range};
    return resource;
  }
  static BindingResource of(VkImageView view) {
    BindingResource resource;
    resource.image = {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
    return resource;
  }
};

// A shader module from embedded SPIR-V (compute and graphics pipelines alike); only needed while the
// pipelines that use it are created.
Status create_shader_module(const Context& context, const std::uint32_t* spirv, std::size_t bytes,
                            const char* debug_name, UniqueHandle<VkShaderModule>& out);

struct ComputePipelineInfo {
  const std::uint32_t* spirv = nullptr;
  std::size_t spirv_bytes = 0;
  std::uint32_t binding_count = 1;          // bindings 0 .. count-1, at most kMaxBindings
  BindingKind bindings[kMaxBindings] = {};  // storage buffers unless set
  std::uint32_t push_constant_bytes = 0;
  const char* debug_name = "carbtf compute pipeline";
};

struct ComputePipeline {
  UniqueHandle<VkDescriptorSetLayout> set_layout;
  UniqueHandle<VkPipelineLayout> layout;
  UniqueHandle<VkPipeline> pipeline;
  std::uint32_t binding_count = 0;
  BindingKind bindings[kMaxBindings] = {};

  static Status create(const Context& context, const ComputePipelineInfo& info, ComputePipeline& out);

  // Binds the pipeline, pushes `resources` (one per binding, binding_count of them) and the push
  // constants. Does not allocate.
  void bind(const Context& context, VkCommandBuffer command_buffer, const BindingResource* resources,
            const void* push_constants, std::uint32_t push_constant_bytes) const noexcept;
};

}  // namespace carbtf::detail
