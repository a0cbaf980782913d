// GPU timestamps around recorded work, for benchmarks. Write timestamps into a command buffer, submit,
// wait, then read the elapsed times. Thread safety: externally synchronized.
#pragma once

#include <cstdint>
#include <vector>

#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

class GpuTimer {
 public:
  GpuTimer() = default;
  // `count` timestamps; fails with device_unsuitable when the queue family has no timestamps.
  static Status create(const Context& context, std::uint32_t count, GpuTimer& out) noexcept;

  void record_reset(VkCommandBuffer command_buffer) const noexcept;
  void record_timestamp(VkCommandBuffer command_buffer, std::uint32_t index,
                        VkPipelineStageFlagBits stage = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT) const noexcept;
  // After the work finished: milliseconds from timestamp `from` to timestamp `to`.
  Status elapsed_ms(std::uint32_t from, std::uint32_t to, double& milliseconds) const noexcept;

 private:
  const Context* context_ = nullptr;
  UniqueHandle<VkQueryPool> pool_;
  std::uint32_t count_ = 0;
};

}  // namespace carbtf
