#include "carbtf/engine/vulkan/gpu_timer.hpp"

#include "vulkan/vk_check.hpp"

namespace carbtf {

Status GpuTimer::create(const Context& context, std::uint32_t count, GpuTimer& out) noexcept {
  if (count == 0) return {ErrorCode::invalid_argument, "a GPU timer needs at least one timestamp"};
  if (context.device_info().timestamp_valid_bits == 0) {
    return {ErrorCode::device_unsuitable,
            context.device_info().name + " has no timestamps on its compute queue"};
  }
  auto info = vk_struct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = count;
  VkQueryPool pool = VK_NULL_HANDLE;
  CARBTF_VK_TRY(context.vk().vkCreateQueryPool(context.device(), &info, nullptr, &pool));
  GpuTimer timer;
  timer.context_ = &context;
  timer.pool_ = UniqueHandle<VkQueryPool>(&context.vk(), context.device(), pool);
  timer.count_ = count;
  context.set_debug_name(timer.pool_, "carbtf gpu timer");
  out = std::move(timer);
  return {};
}

void GpuTimer::record_reset(VkCommandBuffer command_buffer) const noexcept {
  context_->vk().vkCmdResetQueryPool(command_buffer, pool_.get(), 0, count_);
}

void GpuTimer::record_timestamp(VkCommandBuffer command_buffer, std::uint32_t index,
                                VkPipelineStageFlagBits stage) const noexcept {
  context_->vk().vkCmdWriteTimestamp(command_buffer, stage, pool_.get(), index);
}

Status GpuTimer::elapsed_ms(std::uint32_t from, std::uint32_t to, double& milliseconds) const noexcept {
  if (from >= count_ || to >= count_) return {ErrorCode::invalid_argument, "timestamp index out of range"};
  std::uint64_t stamps[2] = {0, 0};
  const VulkanFunctions& vk = context_->vk();
  CARBTF_VK_TRY(vk.vkGetQueryPoolResults(context_->device(), pool_.get(), from, 1, sizeof(std::uint64_t),
                                         &stamps[0], sizeof(std::uint64_t),
                                         VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  CARBTF_VK_TRY(vk.vkGetQueryPoolResults(context_->device(), pool_.get(), to, 1, sizeof(std::uint64_t),
                                         &stamps[1], sizeof(std::uint64_t),
                                         VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const std::uint32_t bits = context_->device_info().timestamp_valid_bits;
  const std::uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  const std::uint64_t ticks = (stamps[1] - stamps[0]) & mask;
  milliseconds = static_cast<double>(ticks) * context_->device_info().timestamp_period_ns * 1e-6;
  return {};
}

}  // namespace carbtf
