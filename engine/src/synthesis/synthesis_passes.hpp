// Internal: the synthesis as a list of passes, each recorded by one function. SubspaceSynthesizer::record
// runs the image passes around, per batch, the batch passes in order, and inserts the timestamps and the
// stage captures between them as each pass's row says. Adding a pass is a recorder here and a row of
// kBatchPasses.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <carbtf_gpu_shared.h>

#include "carbtf/engine/synthesis/synthesis_request.hpp"
#include "synthesis/synthesis_pipelines.hpp"
#include "synthesis/synthesis_plan.hpp"

namespace carbtf::detail {

// Where one batch's tables lie in the table buffer.
struct BatchTables {
  VkDeviceSize fields = 0;
  std::vector<VkDeviceSize> collapse;  // [level]
  VkDeviceSize colour = 0;
};

// What every pass of one batch records with.
struct BatchRecording {
  const Context& context;
  VkCommandBuffer command_buffer;
  const SynthesisPipelines& pipelines;
  const SynthesisPlan& plan;
  const PlannedBatch& batch;
  const BatchTables& tables;
  VkBuffer table_buffer;
  VkBuffer arena;  // the work buffer; the batch uses its first window_bytes
  VkDeviceSize window_bytes;
  VkBuffer frames;  // block initialization values, or VK_NULL_HANDLE
  VkDeviceSize frames_bytes;
  VkImageView output;  // level 0 of the subspace images, in GENERAL
  std::uint64_t seed;
  CarScheme scheme;      // serial or wavefront
  bool noise_in_memory;  // the recursion reads its noise from memory, or a capture compares it
  bool poison;
  std::uint32_t loop_cap;     // iterations one invocation may loop (docs/design.md 6)
  std::uint32_t& dispatches;  // counted, for SynthesisTiming

  // The push constants every pass starts from: the seed, everything else 0.
  gpu::SynthPassParams params() const;
  // Binds `pipeline` with `resources` and `params`, dispatches, counts the dispatch.
  void dispatch(const ComputePipeline& pipeline, const BindingResource* resources,
                const gpu::SynthPassParams& params, std::uint32_t x, std::uint32_t y, std::uint32_t z) const;
  BindingResource arena_binding() const;
  BindingResource field_table() const;
};

using BatchPassRecorder = void (*)(const BatchRecording&);

struct BatchPass {
  const char* name;
  BatchPassRecorder record;
  SynthesisStage completes;  // a capture of this stage is taken after the pass (none: no capture)
  // A timestamp follows the pass where set: the time since the previous one adds to this field of
  // SynthesisTiming (the split points of timing()).
  double SynthesisTiming::*timed_into;
};

// The work buffer reused from the previous batch (and poisoned, if asked).
void record_arena_reset(const BatchRecording& r);
// Each field's initialization frame (block initialization values or zeros).
void record_frames(const BatchRecording& r);
// The fields' noise into memory, where the recursion or a capture reads it from there.
void record_noise(const BatchRecording& r);
// The CAR recursions, run by run, split so that no invocation loops past the cap.
void record_car(const BatchRecording& r);
// The pyramid collapse, coarsest level first.
void record_collapse(const BatchRecording& r);
// The inverse colour transform into the output layers.
void record_colour(const BatchRecording& r);
// The periodic fold's texels, which the colour pass leaves.
void record_fold(const BatchRecording& r);

inline constexpr std::array<BatchPass, 7> kBatchPasses{{
    {"reset", record_arena_reset, SynthesisStage::none, nullptr},
    {"frames", record_frames, SynthesisStage::none, nullptr},
    {"noise", record_noise, SynthesisStage::noise, &SynthesisTiming::prepare_ms},
    {"car", record_car, SynthesisStage::car, &SynthesisTiming::car_ms},
    {"collapse", record_collapse, SynthesisStage::collapse, &SynthesisTiming::collapse_ms},
    {"colour", record_colour, SynthesisStage::none, nullptr},
    {"fold", record_fold, SynthesisStage::none, &SynthesisTiming::colour_ms},
}};

// Timestamps per batch, one after each pass that is timed.
inline constexpr std::uint32_t kTimestampsPerBatch = [] {
  std::uint32_t count = 0;
  for (const BatchPass& pass : kBatchPasses) count += pass.timed_into != nullptr ? 1 : 0;
  return count;
}();

// The subspace images before the batches: previous contents discarded (or set to NaN when poisoned),
// then GENERAL for storage writes.
void record_image_start(const VulkanFunctions& vk, VkCommandBuffer command_buffer, VkImage image,
                        std::uint32_t layers, bool poison);
// After the batches: the images made visible to sampling, copies and later compute, and their mip levels
// blitted from level 0 when they have more than one.
Status record_image_finish(const Context& context, VkCommandBuffer command_buffer, VkImage image,
                           std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                           std::uint32_t mip_levels);

// Copies `bytes` of the work buffer to `destination` at `offset`, between the stage that wrote them and
// the next one (which waits for the copy before overwriting).
void record_capture(const VulkanFunctions& vk, VkCommandBuffer command_buffer, VkBuffer source,
                    VkBuffer destination, VkDeviceSize offset, VkDeviceSize bytes);

}  // namespace carbtf::detail
