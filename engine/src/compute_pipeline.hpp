// Internal: a compute pipeline from embedded SPIR-V, with one push-descriptor set of storage buffers
// and a push-constant block. Every carbtf kernel is built this way, so that recording into a host's
// command buffer needs no descriptor pool.
#pragma once

#include <cstddef>
#include <cstdint>

#include "carbtf/engine/context.hpp"

namespace carbtf::detail {

// Storage-buffer bindings one carbtf kernel may have; recording uses a fixed array, no allocation.
inline constexpr std::uint32_t kMaxStorageBuffers = 8;

struct ComputePipelineInfo {
  const std::uint32_t* spirv = nullptr;
  std::size_t spirv_bytes = 0;
  std::uint32_t storage_buffer_count = 1;  // bindings 0 .. count-1, at most kMaxStorageBuffers
  std::uint32_t push_constant_bytes = 0;
  const char* debug_name = "carbtf compute pipeline";
};

struct ComputePipeline {
  UniqueHandle<VkDescriptorSetLayout> set_layout;
  UniqueHandle<VkPipelineLayout> layout;
  UniqueHandle<VkPipeline> pipeline;

  static Status create(const Context& context, const ComputePipelineInfo& info, ComputePipeline& out);

  // Binds the pipeline, pushes `buffers` (one per binding) and the push constants. Does not allocate.
  void bind(const Context& context, VkCommandBuffer command_buffer, const VkDescriptorBufferInfo* buffers,
            std::uint32_t buffer_count, const void* push_constants, std::uint32_t push_constant_bytes) const noexcept;
};

}  // namespace carbtf::detail
