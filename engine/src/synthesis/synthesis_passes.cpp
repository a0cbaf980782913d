#include "synthesis/synthesis_passes.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <new>

#include "carbtf/engine/vulkan/mip_chain.hpp"
#include "vulkan/barriers.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf::detail {
namespace {

constexpr float kPoison = std::numeric_limits<float>::quiet_NaN();

std::uint32_t groups_for(std::uint64_t items, std::uint64_t per_group) {
  return static_cast<std::uint32_t>((items + per_group - 1) / per_group);
}

// The frame table or, without block initialization values, the field table standing in: no field reads a
// frame then (frame_offset is CARBTF_NO_FRAME), and the binding only needs a valid buffer.
std::array<BindingResource, 3> prepare_bindings(const BatchRecording& r) {
  const BindingResource frames =
      r.frames != VK_NULL_HANDLE ? BindingResource::of(r.frames, 0, r.frames_bytes) : r.field_table();
  return {r.field_table(), r.arena_binding(), frames};
}

BindingResource colour_table(const BatchRecording& r) {
  return BindingResource::of(r.table_buffer, r.tables.colour,
                             r.batch.colour.size() * sizeof(gpu::ColourItemGpu));
}

}  // namespace

gpu::SynthPassParams BatchRecording::params() const {
  gpu::SynthPassParams params{};
  params.seed_lo = static_cast<std::uint32_t>(seed);
  params.seed_hi = static_cast<std::uint32_t>(seed >> 32);
  return params;
}

void BatchRecording::dispatch(const ComputePipeline& pipeline, const BindingResource* resources,
                              const gpu::SynthPassParams& params, std::uint32_t x, std::uint32_t y,
                              std::uint32_t z) const {
  pipeline.bind(context, command_buffer, resources, &params, sizeof(params));
  context.vk().vkCmdDispatch(command_buffer, x, y, z);
  ++dispatches;
}

BindingResource BatchRecording::arena_binding() const {
  return BindingResource::of(arena, 0, window_bytes);
}

BindingResource BatchRecording::field_table() const {
  return BindingResource::of(table_buffer, tables.fields, batch.fields.size() * sizeof(gpu::CarFieldGpu));
}

void record_arena_reset(const BatchRecording& r) {
  const VulkanFunctions& vk = r.context.vk();
  // The previous batch's colour pass (or the clear) must be done before its work memory is reused.
  const StageAccess previous{
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT};
  if (r.poison) {
    memory_barrier(vk, r.command_buffer, previous,
                   {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT});
    std::uint32_t nan_bits = 0;
    std::memcpy(&nan_bits, &kPoison, sizeof(nan_bits));
    vk.vkCmdFillBuffer(r.command_buffer, r.arena, 0, r.window_bytes, nan_bits);
  }
  memory_barrier(
      vk, r.command_buffer, previous,
      {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT});
}

void record_frames(const BatchRecording& r) {
  const auto resources = prepare_bindings(r);
  // The frames as rows of one workgroup width (lavapipe pays per workgroup, so no more of them than the
  // cells need).
  constexpr std::uint32_t kFrameCellsPerRow = gpu::CARBTF_SYNTH_GROUP_X;
  gpu::SynthPassParams params = r.params();
  params.max_cols = kFrameCellsPerRow;
  for (const LevelGroup& group : r.batch.levels) {
    params.begin = group.first;
    params.item_count = group.first + group.count;
    r.dispatch(r.pipelines.prepare, resources.data(), params, kFrameCellsPerRow / gpu::CARBTF_SYNTH_GROUP_X,
               groups_for(groups_for(group.max_frame_cells, kFrameCellsPerRow), gpu::CARBTF_SYNTH_GROUP_Y),
               group.count);
  }
}

void record_noise(const BatchRecording& r) {
  if (!r.noise_in_memory) return;
  compute_to_compute(r.context.vk(), r.command_buffer);
  const auto resources = prepare_bindings(r);
  gpu::SynthPassParams params = r.params();
  params.flags = gpu::CARBTF_PREPARE_NOISE;
  for (const LevelGroup& group : r.batch.levels) {
    params.begin = group.first;
    params.item_count = group.first + group.count;
    // A row of `cols` columns touches at most ceil(pitch / 4) + 1 counter quads (cols <= pitch - 2).
    r.dispatch(r.pipelines.prepare, resources.data(), params,
               groups_for(groups_for(group.max_pitch, 4u) + 1u, gpu::CARBTF_SYNTH_GROUP_X),
               groups_for(group.max_padded_rows, gpu::CARBTF_SYNTH_GROUP_Y), group.count);
  }
}

void record_car(const BatchRecording& r) {
  const BindingResource resources[2] = {r.field_table(), r.arena_binding()};
  const bool serial = r.scheme == CarScheme::serial;
  gpu::SynthPassParams params = r.params();
  for (const CarRun& run : r.batch.car_runs) {
    std::uint64_t total = 0;
    std::uint64_t chunk = 0;
    if (serial) {
      total = run.max_region_quads;
      chunk = r.loop_cap;
    } else {
      // Each step loops over at most ceil(rows / group) rows, plus the step loop itself.
      total = run.max_steps;
      chunk = std::max<std::uint64_t>(
          1, r.loop_cap / (groups_for(run.max_region_rows, gpu::CARBTF_CAR_WAVEFRONT_GROUP) + 1));
    }
    params.field_begin = run.first;
    params.item_count = run.first + run.count;
    for (std::uint64_t begin = 0; begin < total; begin += chunk) {
      compute_to_compute(r.context.vk(), r.command_buffer);
      params.begin = static_cast<std::uint32_t>(begin);
      params.end = static_cast<std::uint32_t>(std::min(total, begin + chunk));
      r.dispatch(r.pipelines.car(r.scheme, run.tap_variant), resources, params,
                 serial ? groups_for(run.count, gpu::CARBTF_CAR_SERIAL_GROUP) : run.count, 1, 1);
    }
  }
}

void record_collapse(const BatchRecording& r) {
  for (std::size_t level = r.batch.collapse.size(); level-- > 0;) {
    const auto& items = r.batch.collapse[level];
    compute_to_compute(r.context.vk(), r.command_buffer);
    const BindingResource resources[2] = {BindingResource::of(r.table_buffer, r.tables.collapse[level],
                                                              items.size() * sizeof(gpu::CollapseItemGpu)),
                                          r.arena_binding()};
    gpu::SynthPassParams params = r.params();
    params.item_count = static_cast<std::uint32_t>(items.size());
    // One invocation per CARBTF_COLLAPSE_SPAN 2 x 2 blocks on even absolute coordinates: n pixels span at
    // most n / 2 + 1 blocks.
    const LevelGroup& group = r.batch.levels[level];
    r.dispatch(
        r.pipelines.collapse, resources, params,
        groups_for(group.max_window_cols / 2 + 1, gpu::CARBTF_SYNTH_GROUP_X * gpu::CARBTF_COLLAPSE_SPAN),
        groups_for(group.max_window_rows / 2 + 1, gpu::CARBTF_SYNTH_GROUP_Y), params.item_count);
  }
}

void record_colour(const BatchRecording& r) {
  compute_to_compute(r.context.vk(), r.command_buffer);
  const BindingResource resources[3] = {colour_table(r), r.arena_binding(), BindingResource::of(r.output)};
  gpu::SynthPassParams params = r.params();
  params.item_count = static_cast<std::uint32_t>(r.batch.colour.size());
  r.dispatch(r.pipelines.colour, resources, params,
             groups_for(r.plan.width, gpu::CARBTF_SYNTH_GROUP_X * gpu::CARBTF_COLOUR_SPAN),
             groups_for(r.plan.height, gpu::CARBTF_SYNTH_GROUP_Y), params.item_count);
}

// No barrier before it: the fold writes the first columns and rows, which the colour pass leaves.
void record_fold(const BatchRecording& r) {
  const std::uint32_t overlap = r.plan.periodic_overlap;
  if (overlap == 0) return;
  const BindingResource resources[3] = {colour_table(r), r.arena_binding(), BindingResource::of(r.output)};
  gpu::SynthPassParams params = r.params();
  params.item_count = static_cast<std::uint32_t>(r.batch.colour.size());
  const std::uint64_t fold_texels = std::uint64_t{overlap} * (r.plan.width + r.plan.height - overlap);
  r.dispatch(r.pipelines.colour_fold, resources, params, groups_for(fold_texels, gpu::CARBTF_FOLD_GROUP), 1,
             params.item_count);
}

void record_image_start(const VulkanFunctions& vk, VkCommandBuffer command_buffer, VkImage image,
                        std::uint32_t layers, bool poison) {
  const ColourRange all{0, 1, 0, layers};
  const StageAccess nothing{VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0};
  const StageAccess shaders{VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                            VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT};
  if (!poison) {
    transition_colour(vk, command_buffer, image, all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                      nothing, shaders);
    return;
  }
  const StageAccess clear{VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT};
  transition_colour(vk, command_buffer, image, all, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, nothing, clear);
  VkClearColorValue nan{};
  nan.float32[0] = nan.float32[1] = nan.float32[2] = nan.float32[3] = kPoison;
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
  vk.vkCmdClearColorImage(command_buffer, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &nan, 1, &range);
  transition_colour(vk, command_buffer, image, all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_GENERAL, clear, shaders);
}

Status record_image_finish(const Context& context, VkCommandBuffer command_buffer, VkImage image,
                           std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                           std::uint32_t mip_levels) {
  const VulkanFunctions& vk = context.vk();
  const StageAccess readers{VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                                VK_PIPELINE_STAGE_TRANSFER_BIT,
                            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT};
  memory_barrier(vk, command_buffer, {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                 readers);
  if (mip_levels <= 1) return {};
  // Level 0 is the blits' source, then GENERAL again like the levels they write.
  const ColourRange level0{0, 1, 0, layers};
  const StageAccess blit_source{VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT};
  transition_colour(vk, command_buffer, image, level0, VK_IMAGE_LAYOUT_GENERAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT}, blit_source);
  std::vector<std::uint32_t> all;
  try {
    all.resize(layers);
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory recording the mip levels"};
  }
  for (std::uint32_t i = 0; i < layers; ++i) all[i] = i;
  CARBTF_TRY(record_mip_blits(context, command_buffer,
                              {image, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, width, height}, image, 1,
                              mip_levels - 1, all, VK_IMAGE_LAYOUT_GENERAL));
  transition_colour(vk, command_buffer, image, level0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_GENERAL, blit_source, readers);
  return {};
}

void record_capture(const VulkanFunctions& vk, VkCommandBuffer command_buffer, VkBuffer source,
                    VkBuffer destination, VkDeviceSize offset, VkDeviceSize bytes) {
  memory_barrier(vk, command_buffer, {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                 {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT});
  const VkBufferCopy region{0, offset, bytes};
  vk.vkCmdCopyBuffer(command_buffer, source, destination, 1, &region);
  memory_barrier(vk, command_buffer, {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT},
                 {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT});
}

}  // namespace carbtf::detail
