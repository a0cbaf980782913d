#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <new>
#include <string>

#include <carbtf_gpu_shared.h>

#include "carbtf/engine/vulkan/gpu_timer.hpp"
#include "carbtf/engine/vulkan/mip_chain.hpp"
#include "synthesis/image_readback.hpp"
#include "synthesis/synthesis_passes.hpp"
#include "synthesis/synthesis_pipelines.hpp"
#include "synthesis/synthesis_plan.hpp"
#include "vulkan/barriers.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {
namespace {

// lavapipe stops a loop silently past 65,535 iterations per invocation (docs/design.md 6); stay below.
constexpr std::uint32_t kSafeLoopIterations = 60000;
// Offsets in the kernels are 32-bit element indices.
constexpr VkDeviceSize kMaxWindowBytes = VkDeviceSize{1} << 31;

using detail::BatchTables;
using detail::kTimestampsPerBatch;

std::uint32_t ceil_div(std::uint64_t a, std::uint64_t b) {
  return static_cast<std::uint32_t>((a + b - 1) / b);
}

VkDeviceSize align_up(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

}  // namespace

const char* car_scheme_name(CarScheme scheme) noexcept {
  switch (scheme) {
    case CarScheme::automatic:
      return "automatic";
    case CarScheme::serial:
      return "serial";
    case CarScheme::wavefront:
      return "wavefront";
  }
  return "unknown";
}

struct SubspaceSynthesizer::Pipelines : detail::SynthesisPipelines {};

struct SubspaceSynthesizer::Prepared {
  detail::SynthesisPlan plan;
  std::vector<BatchTables> tables;
  std::uint64_t seed = 0;
  CarScheme scheme = CarScheme::serial;
  bool poison = false;
  Buffer table_buffer;
  Buffer frames;  // block initialization values, when the request has them
  Buffer arena;
  Buffer capture;  // host copy of every batch's window after request.capture's stage
  std::vector<VkDeviceSize> capture_offsets;
  SynthesisStage capture_stage = SynthesisStage::none;
  Image image;
  Buffer readback;  // host memory the results come back through; kept for the next run, as the arena
  GpuTimer timer;
  bool timer_ready = false;
  std::uint32_t dispatches = 0;
};

SubspaceSynthesizer::~SubspaceSynthesizer() = default;

Status SubspaceSynthesizer::create(Context& context, std::unique_ptr<SubspaceSynthesizer>& out) noexcept {
  try {
    std::unique_ptr<SubspaceSynthesizer> synthesizer(new SubspaceSynthesizer());
    synthesizer->context_ = &context;
    synthesizer->pipelines_ = std::make_unique<Pipelines>();
    CARBTF_TRY(synthesizer->pipelines_->create(context));
    out = std::move(synthesizer);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while creating the subspace synthesizer"};
  }
}

void SubspaceSynthesizer::release() noexcept {
  prepared_.reset();
}

Status SubspaceSynthesizer::prepare(const Material& material, const SynthesisRequest& request) noexcept {
  try {
    // The work buffer, the image and the readback buffer of the last preparation serve again where they
    // are large enough: fresh device memory costs its first touch on every run (lavapipe: about a fifth
    // of a 20 x 512^2 synthesis, in page faults), and a host that synthesizes again and again asks for
    // the same sizes.
    Buffer previous_arena;
    Image previous_image;
    Buffer previous_readback;
    if (prepared_) {
      previous_arena = std::move(prepared_->arena);
      previous_image = std::move(prepared_->image);
      previous_readback = std::move(prepared_->readback);
    }
    prepared_.reset();
    const DeviceInfo& device = context_->device_info();
    const VkDeviceSize alignment = std::max<VkDeviceSize>(device.min_storage_buffer_offset_alignment, 16);
    VkDeviceSize window_bytes = std::min(device.max_storage_buffer_range, kMaxWindowBytes);
    if (max_batch_bytes_ > 0) window_bytes = std::min(window_bytes, max_batch_bytes_);

    auto prepared = std::make_unique<Prepared>();
    CARBTF_TRY(detail::plan_synthesis(material, request, window_bytes, prepared->plan));
    const detail::SynthesisPlan& plan = prepared->plan;
    if (plan.width > device.max_image_dimension_2d || plan.height > device.max_image_dimension_2d ||
        plan.subspaces.size() > device.max_image_array_layers) {
      return {ErrorCode::invalid_argument, std::to_string(plan.width) + "x" + std::to_string(plan.height) +
                                               " with " + std::to_string(plan.subspaces.size()) +
                                               " layers exceeds " + device.name + "'s image limits (" +
                                               std::to_string(device.max_image_dimension_2d) + " texels, " +
                                               std::to_string(device.max_image_array_layers) + " layers)"};
    }
    for (const detail::PlannedBatch& batch : plan.batches) {
      const std::uint32_t groups_y =
          std::max(ceil_div(batch.levels[0].max_padded_rows, gpu::CARBTF_SYNTH_GROUP_Y),
                   ceil_div(plan.height, gpu::CARBTF_SYNTH_GROUP_Y));
      const std::uint32_t groups_x = std::max(ceil_div(batch.levels[0].max_pitch, gpu::CARBTF_SYNTH_GROUP_X),
                                              ceil_div(plan.width, gpu::CARBTF_SYNTH_GROUP_X));
      if (groups_x > device.max_compute_group_count[0] || groups_y > device.max_compute_group_count[1] ||
          batch.fields.size() > device.max_compute_group_count[2] ||
          batch.fields.size() > device.max_compute_group_count[0]) {
        return {ErrorCode::invalid_argument,
                "the synthesis needs more workgroups than " + device.name + " dispatches"};
      }
    }
    prepared->seed = request.seed;
    prepared->capture_stage = request.capture;
    if (request.capture != SynthesisStage::none) {
      VkDeviceSize capture_bytes = 0;
      for (const detail::PlannedBatch& batch : plan.batches) {
        prepared->capture_offsets.push_back(capture_bytes);
        capture_bytes += batch.window_floats * sizeof(float);
      }
      CARBTF_TRY(Buffer::create(*context_,
                                {capture_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::host_readback,
                                 "carbtf synthesis capture"},
                                prepared->capture));
    }
    prepared->poison = request.poison;
    prepared->scheme = request.scheme;
    if (prepared->scheme == CarScheme::automatic) {
      prepared->scheme =
          device.type == VK_PHYSICAL_DEVICE_TYPE_CPU ? CarScheme::serial : CarScheme::wavefront;
    }
    for (const detail::PlannedBatch& batch : plan.batches) {
      for (const detail::CarRun& run : batch.car_runs)
        CARBTF_TRY(pipelines_->build_car(*context_, prepared->scheme, run.tap_variant));
    }

    // Tables: per batch the fields, each level's collapse items and the colour items, each aligned.
    VkDeviceSize table_bytes = 0;
    auto reserve = [&](VkDeviceSize bytes) {
      const VkDeviceSize at = table_bytes;
      table_bytes = align_up(table_bytes + std::max<VkDeviceSize>(bytes, 16), alignment);
      return at;
    };
    for (const detail::PlannedBatch& batch : plan.batches) {
      BatchTables tables;
      tables.fields = reserve(batch.fields.size() * sizeof(gpu::CarFieldGpu));
      for (const auto& items : batch.collapse)
        tables.collapse.push_back(reserve(items.size() * sizeof(gpu::CollapseItemGpu)));
      tables.colour = reserve(batch.colour.size() * sizeof(gpu::ColourItemGpu));
      prepared->tables.push_back(std::move(tables));
    }
    CARBTF_TRY(Buffer::create(*context_,
                              {table_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::host_upload,
                               "carbtf synthesis tables"},
                              prepared->table_buffer));
    auto* bytes = static_cast<std::uint8_t*>(prepared->table_buffer.mapped());
    for (std::size_t b = 0; b < plan.batches.size(); ++b) {
      const detail::PlannedBatch& batch = plan.batches[b];
      const BatchTables& tables = prepared->tables[b];
      for (std::size_t f = 0; f < batch.fields.size(); ++f) {
        std::memcpy(bytes + tables.fields + f * sizeof(gpu::CarFieldGpu), &batch.fields[f].gpu,
                    sizeof(gpu::CarFieldGpu));
      }
      for (std::size_t level = 0; level < batch.collapse.size(); ++level) {
        std::memcpy(bytes + tables.collapse[level], batch.collapse[level].data(),
                    batch.collapse[level].size() * sizeof(gpu::CollapseItemGpu));
      }
      std::memcpy(bytes + tables.colour, batch.colour.data(),
                  batch.colour.size() * sizeof(gpu::ColourItemGpu));
    }

    if (!request.initial_values.empty()) {
      const VkDeviceSize frame_bytes = request.initial_values.size_bytes();
      if (frame_bytes > device.max_storage_buffer_range) {
        return {ErrorCode::invalid_argument, "the block initialization values exceed " + device.name +
                                                 "'s storage-buffer range; synthesize smaller blocks"};
      }
      CARBTF_TRY(Buffer::create(*context_,
                                {frame_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::host_upload,
                                 "carbtf block initialization values"},
                                prepared->frames));
      std::memcpy(prepared->frames.mapped(), request.initial_values.data(), frame_bytes);
    }
    const VkDeviceSize arena_bytes = plan.window_floats * sizeof(float);
    if (previous_arena.handle() != VK_NULL_HANDLE && previous_arena.size() >= arena_bytes) {
      prepared->arena = std::move(previous_arena);
    } else {
      previous_arena = {};  // released before the new one is allocated
      CARBTF_TRY(Buffer::create(*context_,
                                {arena_bytes,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 MemoryUsage::device_local, "carbtf synthesis fields"},
                                prepared->arena));
    }
    ImageCreateInfo image_info;
    image_info.width = plan.width;
    image_info.height = plan.height;
    image_info.array_layers = static_cast<std::uint32_t>(plan.subspaces.size());
    image_info.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    if (request.mip_levels != 1 && can_blit_mips(*context_, image_info.format)) {
      const std::uint32_t possible = mip_level_count(plan.width, plan.height);
      image_info.mip_levels = request.mip_levels == 0 ? possible : std::min(request.mip_levels, possible);
    }
    image_info.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    image_info.debug_name = "carbtf subspace images";
    const ImageCreateInfo& previous_info = previous_image.info();
    if (previous_image.handle() != VK_NULL_HANDLE && previous_info.width == image_info.width &&
        previous_info.height == image_info.height && previous_info.array_layers == image_info.array_layers &&
        previous_info.mip_levels == image_info.mip_levels) {
      prepared->image = std::move(previous_image);
    } else {
      previous_image = {};
      CARBTF_TRY(Image::create(*context_, image_info, prepared->image));
    }
    if (device.timestamp_valid_bits > 0) {
      CARBTF_TRY(GpuTimer::create(*context_,
                                  1 + kTimestampsPerBatch * static_cast<std::uint32_t>(plan.batches.size()),
                                  prepared->timer));
      prepared->timer_ready = true;
    }
    prepared->readback = std::move(previous_readback);  // read_back_in_row_bands() replaces it if too small
    prepared_ = std::move(prepared);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while planning the synthesis"};
  }
}

Status SubspaceSynthesizer::read_band(std::uint32_t subspace, std::uint32_t level, std::uint32_t channel,
                                      std::vector<float>& out, std::uint32_t& rows,
                                      std::uint32_t& cols) const noexcept {
  if (!prepared_ || prepared_->capture_stage == SynthesisStage::none) {
    return {ErrorCode::invalid_argument,
            "read_band() needs a synthesize() or run() whose request captured a stage"};
  }
  const Prepared& p = *prepared_;
  CARBTF_TRY(p.capture.invalidate_for_host_read());
  for (std::size_t b = 0; b < p.plan.batches.size(); ++b) {
    for (const detail::PlannedField& field : p.plan.batches[b].fields) {
      if (field.subspace != subspace || field.level != level || field.channel != channel) continue;
      try {
        rows = static_cast<std::uint32_t>(field.window.rows);
        cols = static_cast<std::uint32_t>(field.window.cols);
        out.resize(std::size_t{rows} * cols);
        const float* base =
            static_cast<const float*>(p.capture.mapped()) + p.capture_offsets[b] / sizeof(float);
        for (std::uint32_t r = 0; r < rows; ++r) {
          std::memcpy(&out[std::size_t{r} * cols],
                      base + field.window_element() + std::size_t{r} * field.gpu.pitch, cols * sizeof(float));
        }
        return {};
      } catch (const std::bad_alloc&) {
        return {ErrorCode::out_of_host_memory, "out of host memory while reading a band"};
      }
    }
  }
  return {ErrorCode::invalid_argument, "band (subspace " + std::to_string(subspace) + ", level " +
                                           std::to_string(level) + ", channel " + std::to_string(channel) +
                                           ") was not synthesized"};
}

Status SubspaceSynthesizer::record(VkCommandBuffer command_buffer, bool timed) const noexcept {
  if (!prepared_) return {ErrorCode::invalid_argument, "record() before a successful prepare()"};
  Prepared& p = *prepared_;
  const VulkanFunctions& vk = context_->vk();
  const detail::SynthesisPlan& plan = p.plan;
  timed = timed && p.timer_ready;
  p.dispatches = 0;
  if (timed) {
    p.timer.record_reset(command_buffer);
    p.timer.record_timestamp(command_buffer, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
  }
  const auto layers = static_cast<std::uint32_t>(plan.subspaces.size());
  detail::record_image_start(vk, command_buffer, p.image.handle(), layers, p.poison);
  std::uint32_t stamp = 1;
  for (std::size_t b = 0; b < plan.batches.size(); ++b) {
    const detail::PlannedBatch& batch = plan.batches[b];
    const detail::BatchRecording recording{
        .context = *context_,
        .command_buffer = command_buffer,
        .pipelines = *pipelines_,
        .plan = plan,
        .batch = batch,
        .tables = p.tables[b],
        .table_buffer = p.table_buffer.handle(),
        .arena = p.arena.handle(),
        .window_bytes = batch.window_floats * sizeof(float),
        .frames = p.frames.handle(),
        .frames_bytes = p.frames.handle() != VK_NULL_HANDLE ? p.frames.size() : 0,
        .output = p.image.level0_view(),
        .seed = p.seed,
        .scheme = p.scheme,
        .noise_in_memory = p.scheme == CarScheme::wavefront || p.capture_stage == SynthesisStage::noise,
        .poison = p.poison,
        .loop_cap = max_loop_iterations_ > 0 ? max_loop_iterations_ : kSafeLoopIterations,
        .dispatches = p.dispatches};
    for (const detail::BatchPass& pass : detail::kBatchPasses) {
      pass.record(recording);
      if (pass.timed_into != nullptr) {
        if (timed) p.timer.record_timestamp(command_buffer, stamp, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        ++stamp;
      }
      if (pass.completes != SynthesisStage::none && pass.completes == p.capture_stage) {
        detail::record_capture(vk, command_buffer, p.arena.handle(), p.capture.handle(), p.capture_offsets[b],
                               recording.window_bytes);
      }
    }
  }
  return detail::record_image_finish(*context_, command_buffer, p.image.handle(), plan.width, plan.height,
                                     layers, p.image.info().mip_levels);
}

VkImage SubspaceSynthesizer::image() const noexcept {
  return prepared_ ? prepared_->image.handle() : VK_NULL_HANDLE;
}
std::uint32_t SubspaceSynthesizer::mip_levels() const noexcept {
  return prepared_ ? prepared_->image.info().mip_levels : 0;
}

VkImageView SubspaceSynthesizer::image_view() const noexcept {
  return prepared_ ? prepared_->image.view() : VK_NULL_HANDLE;
}
std::uint32_t SubspaceSynthesizer::width() const noexcept {
  return prepared_ ? prepared_->plan.width : 0;
}
std::uint32_t SubspaceSynthesizer::height() const noexcept {
  return prepared_ ? prepared_->plan.height : 0;
}
std::uint32_t SubspaceSynthesizer::periodic_overlap() const noexcept {
  return prepared_ ? prepared_->plan.periodic_overlap : 0;
}
CarScheme SubspaceSynthesizer::scheme() const noexcept {
  return prepared_ ? prepared_->scheme : CarScheme::automatic;
}
std::uint32_t SubspaceSynthesizer::batch_count() const noexcept {
  return prepared_ ? static_cast<std::uint32_t>(prepared_->plan.batches.size()) : 0;
}

std::uint32_t SubspaceSynthesizer::layer_of(std::uint32_t subspace) const noexcept {
  if (!prepared_) return std::numeric_limits<std::uint32_t>::max();
  const auto& subspaces = prepared_->plan.subspaces;
  const auto it = std::find(subspaces.begin(), subspaces.end(), subspace);
  return it == subspaces.end() ? std::numeric_limits<std::uint32_t>::max()
                               : static_cast<std::uint32_t>(it - subspaces.begin());
}

Status SubspaceSynthesizer::record_interpolation(VkCommandBuffer command_buffer, const Material& material,
                                                 const PairWeights& weights,
                                                 VkImageView target) const noexcept {
  if (!prepared_)
    return {ErrorCode::invalid_argument, "record_interpolation() before a successful prepare()"};
  gpu::InterpolateParams params{};
  params.width = prepared_->plan.width;
  params.height = prepared_->plan.height;
  for (int k = 0; k < 9; ++k) {
    params.weight[k] = weights.weight[k];
    if (weights.weight[k] == 0.0f) continue;
    if (weights.light[k] >= material.lights.size() || weights.view[k] >= material.views.size()) {
      return {ErrorCode::invalid_argument, "interpolation pair out of the material's direction range"};
    }
    const std::uint32_t subspace = subspace_of(material, weights.light[k], weights.view[k]);
    const std::uint32_t layer = layer_of(subspace);
    if (layer == std::numeric_limits<std::uint32_t>::max()) {
      return {ErrorCode::invalid_argument, "interpolation needs subspace image " + std::to_string(subspace) +
                                               ", which was not synthesized"};
    }
    params.layer[k] = layer;
  }
  const detail::BindingResource resources[2] = {detail::BindingResource::of(prepared_->image.level0_view()),
                                                detail::BindingResource::of(target)};
  pipelines_->interpolate.bind(*context_, command_buffer, resources, &params, sizeof(params));
  context_->vk().vkCmdDispatch(command_buffer, ceil_div(params.width, gpu::CARBTF_SYNTH_GROUP_X),
                               ceil_div(params.height, gpu::CARBTF_SYNTH_GROUP_Y), 1);
  return {};
}

Status SubspaceSynthesizer::timing(SynthesisTiming& out) const noexcept {
  out = {};
  if (!prepared_) return {ErrorCode::invalid_argument, "timing() before a successful prepare()"};
  out.batches = static_cast<std::uint32_t>(prepared_->plan.batches.size());
  out.dispatches = prepared_->dispatches;
  if (!prepared_->timer_ready) return {};
  const GpuTimer& timer = prepared_->timer;
  // The stamps record() wrote: 0 at the start, then one after each timed pass of each batch.
  std::uint32_t previous = 0, stamp = 1;
  for (std::uint32_t b = 0; b < out.batches; ++b) {
    for (const detail::BatchPass& pass : detail::kBatchPasses) {
      if (pass.timed_into == nullptr) continue;
      double ms = 0.0;
      CARBTF_TRY(timer.elapsed_ms(previous, stamp, ms));
      out.*pass.timed_into += ms;
      previous = stamp++;
    }
  }
  CARBTF_TRY(timer.elapsed_ms(0, previous, out.total_ms));
  return {};
}

VkDeviceSize SubspaceSynthesizer::readback_bytes() const noexcept {
  return max_readback_bytes_ != 0 ? max_readback_bytes_ : detail::kDefaultReadbackBytes;
}

Status SubspaceSynthesizer::synthesize(const Material& material, const SynthesisRequest& request,
                                       SynthesizedImages& out, SynthesisTiming* timing_out) noexcept {
  CARBTF_TRY(prepare(material, request));
  try {
    const detail::SynthesisPlan& plan = prepared_->plan;
    const auto layers = static_cast<std::uint32_t>(plan.subspaces.size());
    // `out`'s vectors are resized, not rebuilt: a caller that synthesizes again into the same result
    // keeps its memory, where fresh vectors cost the page faults of tens of megabytes each time (up to
    // 160 ms of a 20 x 512^2 synthesis on lavapipe, depending on the allocator). Every element kept is
    // overwritten by the readback.
    out.width = plan.width;
    out.height = plan.height;
    out.channels.assign(material.subspaces.size(), 0);
    out.images.resize(material.subspaces.size());
    for (std::size_t layer = 0; layer < layers; ++layer) {
      const std::uint32_t s = plan.subspaces[layer];
      out.channels[s] = plan.channels[layer];
      out.images[s].resize(std::size_t{plan.width} * plan.height * plan.channels[layer]);
    }
    for (std::size_t s = 0; s < out.images.size(); ++s) {
      if (out.channels[s] == 0) out.images[s].clear();
    }
    const auto record_work = [&](VkCommandBuffer command_buffer) {
      return record(command_buffer, timing_out != nullptr);
    };
    CARBTF_TRY(detail::read_back_in_row_bands(
        *context_, prepared_->image.handle(), plan.width, plan.height, layers, readback_bytes(),
        prepared_->readback, record_work, [&](const float* rgba, std::uint32_t row0, std::uint32_t rows) {
          const std::size_t pixels = std::size_t{plan.width} * rows;
          for (std::size_t layer = 0; layer < layers; ++layer) {
            const std::uint32_t s = plan.subspaces[layer];
            detail::unpack_rgba(rgba + layer * pixels * 4, pixels, plan.channels[layer],
                                std::size_t{row0} * plan.width, out.images[s]);
          }
        }));
    if (timing_out) CARBTF_TRY(timing(*timing_out));
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while reading back subspace images"};
  }
}

Status SubspaceSynthesizer::run(const Material& material, const SynthesisRequest& request,
                                SynthesisTiming* timing_out) noexcept {
  CARBTF_TRY(prepare(material, request));
  CARBTF_TRY(context_->submit_and_wait(
      [&](VkCommandBuffer command_buffer) { return record(command_buffer, timing_out != nullptr); }));
  if (timing_out) CARBTF_TRY(timing(*timing_out));
  return {};
}

Status SubspaceSynthesizer::interpolate(const Material& material, const PairWeights& weights,
                                        std::vector<float>& out) noexcept {
  if (!prepared_) return {ErrorCode::invalid_argument, "interpolate() before synthesize()"};
  try {
    const detail::SynthesisPlan& plan = prepared_->plan;
    ImageCreateInfo info;
    info.width = plan.width;
    info.height = plan.height;
    info.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    info.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    info.debug_name = "carbtf interpolated image";
    Image target;
    CARBTF_TRY(Image::create(*context_, info, target));
    std::uint32_t channels = 0;
    for (int k = 0; k < 9; ++k) {
      if (weights.weight[k] != 0.0f) {
        channels = plan.channels[layer_of(subspace_of(material, weights.light[k], weights.view[k]))];
        break;
      }
    }
    if (channels == 0) channels = plan.channels[0];
    out.assign(std::size_t{plan.width} * plan.height * channels, 0.0f);
    const VulkanFunctions& vk = context_->vk();
    const auto record_work = [&](VkCommandBuffer command_buffer) -> Status {
      detail::transition_colour(vk, command_buffer, target.handle(), {}, VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_GENERAL, {VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0},
                                {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT});
      return record_interpolation(command_buffer, material, weights, target.view());
    };
    CARBTF_TRY(detail::read_back_in_row_bands(
        *context_, target.handle(), plan.width, plan.height, 1, readback_bytes(), prepared_->readback,
        record_work, [&](const float* rgba, std::uint32_t row0, std::uint32_t rows) {
          detail::unpack_rgba(rgba, std::size_t{plan.width} * rows, channels, std::size_t{row0} * plan.width,
                              out);
        }));
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while interpolating"};
  }
}

}  // namespace carbtf
