#include "carbtf/engine/synthesis/noise_generator.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include <carbtf_gpu_shared.h>
#include <carbtf_spirv/noise_field.h>

#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/gpu_timer.hpp"
#include "vulkan/barriers.hpp"
#include "vulkan/compute_pipeline.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {

struct NoiseGenerator::Pipeline {
  detail::ComputePipeline compute;
};

NoiseGenerator::~NoiseGenerator() = default;

Status NoiseGenerator::create(Context& context, std::unique_ptr<NoiseGenerator>& out) noexcept {
  try {
    std::unique_ptr<NoiseGenerator> generator(new NoiseGenerator());
    generator->context_ = &context;
    generator->pipeline_ = std::make_unique<Pipeline>();
    detail::ComputePipelineInfo info;
    info.spirv = carbtf_spirv_noise_field;
    info.spirv_bytes = sizeof(carbtf_spirv_noise_field);
    info.binding_count = 1;
    info.push_constant_bytes = sizeof(gpu::NoiseFieldParams);
    info.debug_name = "carbtf noise_field";
    CARBTF_TRY(detail::ComputePipeline::create(context, info, generator->pipeline_->compute));
    out = std::move(generator);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while creating the noise generator"};
  }
}

Status NoiseGenerator::record(VkCommandBuffer command_buffer, const NoiseBlock& block, VkBuffer destination,
                              VkDeviceSize offset) const noexcept {
  if (block.width == 0 || block.height == 0) return {};
  if (offset % sizeof(float) != 0) {
    return {ErrorCode::invalid_argument, "noise destination offset must be a multiple of 4 bytes"};
  }
  const DeviceInfo& device = context_->device_info();
  const VkDeviceSize alignment = std::max<VkDeviceSize>(device.min_storage_buffer_offset_alignment, 4);
  const VkDeviceSize row_bytes = VkDeviceSize{block.width} * sizeof(float);
  // A chunk's bound range is its rows plus at most `alignment` bytes of lead-in; it must fit the
  // device's storage range, and its group counts the device's dispatch limits.
  if (block.width > std::uint64_t{device.max_compute_group_count[0]} * gpu::CARBTF_NOISE_GROUP_X ||
      row_bytes + alignment > device.max_storage_buffer_range) {
    return {ErrorCode::invalid_argument, "noise block width " + std::to_string(block.width) +
                                             " exceeds what " + device.name + " can dispatch"};
  }
  std::uint64_t rows_per_chunk = (device.max_storage_buffer_range - alignment) / row_bytes;
  rows_per_chunk = std::min<std::uint64_t>(
      rows_per_chunk, std::uint64_t{device.max_compute_group_count[1]} * gpu::CARBTF_NOISE_GROUP_Y);
  if (max_rows_per_dispatch_ > 0)
    rows_per_chunk = std::min<std::uint64_t>(rows_per_chunk, max_rows_per_dispatch_);

  const std::uint64_t seed = block.seed;
  for (std::uint64_t first_row = 0; first_row < block.height; first_row += rows_per_chunk) {
    const auto rows =
        static_cast<std::uint32_t>(std::min<std::uint64_t>(rows_per_chunk, block.height - first_row));
    const VkDeviceSize chunk_offset = offset + first_row * row_bytes;
    const VkDeviceSize bound_offset = chunk_offset / alignment * alignment;

    gpu::NoiseFieldParams params{};
    params.seed_lo = static_cast<std::uint32_t>(seed);
    params.seed_hi = static_cast<std::uint32_t>(seed >> 32);
    params.field_id = block.field_id;
    params.row0 = static_cast<std::uint32_t>(block.row0) + static_cast<std::uint32_t>(first_row);
    params.col0 = static_cast<std::uint32_t>(block.col0);
    params.width = block.width;
    params.height = rows;
    params.row_pitch = block.width;
    params.element_offset = static_cast<std::uint32_t>((chunk_offset - bound_offset) / sizeof(float));

    const auto output = detail::BindingResource::of(destination, bound_offset,
                                                    (chunk_offset - bound_offset) + rows * row_bytes);
    pipeline_->compute.bind(*context_, command_buffer, &output, &params, sizeof(params));
    const std::uint32_t quads = gpu::carbtf_noise_quads(params.col0, block.width);
    context_->vk().vkCmdDispatch(command_buffer,
                                 (quads + gpu::CARBTF_NOISE_GROUP_X - 1) / gpu::CARBTF_NOISE_GROUP_X,
                                 (rows + gpu::CARBTF_NOISE_GROUP_Y - 1) / gpu::CARBTF_NOISE_GROUP_Y, 1);
  }
  return {};
}

Status NoiseGenerator::generate(const NoiseBlock& block, std::vector<float>& out,
                                double* gpu_milliseconds) noexcept {
  try {
    const VkDeviceSize bytes = VkDeviceSize{block.width} * block.height * sizeof(float);
    if (bytes == 0) {
      out.clear();
      return {};
    }
    Buffer buffer;
    CARBTF_TRY(Buffer::create(
        *context_,
        {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::host_readback, "carbtf noise readback"},
        buffer));
    GpuTimer timer;
    const bool timed = gpu_milliseconds && context_->device_info().timestamp_valid_bits > 0;
    if (timed) CARBTF_TRY(GpuTimer::create(*context_, 2, timer));

    auto record_work = [&](VkCommandBuffer command_buffer) -> Status {
      if (timed) {
        timer.record_reset(command_buffer);
        timer.record_timestamp(command_buffer, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
      }
      CARBTF_TRY(record(command_buffer, block, buffer.handle(), 0));
      if (timed) timer.record_timestamp(command_buffer, 1, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
      detail::memory_barrier(context_->vk(), command_buffer,
                             {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                             {VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT});
      return {};
    };
    CARBTF_TRY(context_->submit_and_wait(record_work));
    CARBTF_TRY(buffer.invalidate_for_host_read());
    out.resize(static_cast<std::size_t>(block.width) * block.height);
    std::memcpy(out.data(), buffer.mapped(), static_cast<std::size_t>(bytes));
    if (timed) CARBTF_TRY(timer.elapsed_ms(0, 1, *gpu_milliseconds));
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while generating noise"};
  }
}

}  // namespace carbtf
