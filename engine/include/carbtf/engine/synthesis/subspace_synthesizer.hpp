// GPU synthesis of subspace images (docs/design.md 4.4): for a material, a seed and a block of the unbounded
// texture, every requested subspace image, computed to the CPU reference's specification
// (analysis/reference/include/carbtf/reference/subspace_synthesis.hpp): noise, one CAR recursion per
// band and level, pyramid collapse, inverse colour transform. Then the 9-weight interpolation of those
// images for any (light, view).
//
// Work goes in batches: each batch's fields must fit one storage-buffer binding (128 MiB on lavapipe),
// so large requests run as several batches in the same command buffer, reusing one work buffer.
//
// Use: create() once per context; prepare() a request (host work and allocations only); record() into
// a command buffer of yours, or call synthesize() to submit, wait and read back.
//
// Lifetime: the synthesizer must outlive the execution of every command buffer it recorded into, and
// must not be prepared again while one is pending. Destroy it before the Context.
// Thread safety: externally synchronized (one thread at a time per synthesizer).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/synthesis/synthesis_block.hpp"
#include "carbtf/engine/synthesis/synthesis_request.hpp"
#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

class SubspaceSynthesizer {
 public:
  // Builds the compute pipelines on `context`, which must outlive the synthesizer.
  static Status create(Context& context, std::unique_ptr<SubspaceSynthesizer>& out) noexcept;
  ~SubspaceSynthesizer();

  // Plans `request` for `material` and (re)allocates the output image, the work buffer and the item
  // tables. The previous preparation's work buffer serves again when it is large enough, and its image
  // when the size and layer count match (image() then returns the same handle, its contents to be
  // overwritten by the next record()). Copies what it needs from `material`. Fails with invalid_argument for
  // a request the material or the device cannot serve (unknown subspace, too many channels or neighbours, an
  // image beyond the device's limits), naming the cause.
  Status prepare(const Material& material, const SynthesisRequest& request) noexcept;

  // Frees the prepared synthesis: its image, work buffer and tables (image() is null afterwards). The
  // caller must have finished any work recorded from it. A later prepare() allocates again.
  void release() noexcept;

  // Records the prepared synthesis. The output image goes from any layout to VK_IMAGE_LAYOUT_GENERAL
  // (its previous contents are discarded) and ends visible to compute and fragment shader reads. With
  // `timed`, writes GPU timestamps that timing() reads after the work has finished.
  Status record(VkCommandBuffer command_buffer, bool timed = false) const noexcept;

  // The output: an RGBA32F 2D-array image, one layer per requested subspace (layer_of), channels
  // beyond the model's own set to 0 and alpha to 1. Null before a successful prepare().
  VkImage image() const noexcept;
  VkImageView image_view() const noexcept;  // all mip levels
  std::uint32_t mip_levels()
      const noexcept;  // of the image (SynthesisRequest::mip_levels); 0 before prepare()
  // The layer of subspace `subspace`, or UINT32_MAX when it was not requested.
  std::uint32_t layer_of(std::uint32_t subspace) const noexcept;
  std::uint32_t width() const noexcept;
  std::uint32_t height() const noexcept;
  // The prepared request's periodic overlap: > 0 when the images tile (SynthesisBlock::periodic_overlap).
  std::uint32_t periodic_overlap() const noexcept;
  CarScheme scheme() const noexcept;  // the scheme the prepared request runs (never automatic)
  std::uint32_t batch_count() const noexcept;

  // Records the 9-weight interpolation of the prepared images into layer 0 of `target` (an RGBA32F
  // storage image of at least width() x height(), in VK_IMAGE_LAYOUT_GENERAL). Must follow record()
  // in execution order. Fails when a pair with a non-zero weight falls in a subspace not synthesized.
  Status record_interpolation(VkCommandBuffer command_buffer, const Material& material,
                              const PairWeights& weights, VkImageView target) const noexcept;

  // After a timed record() has executed: the GPU time per stage.
  Status timing(SynthesisTiming& out) const noexcept;

  // Convenience: prepare, record, submit and wait, leaving the images on the device (image(),
  // read_band(), interpolate()): for captures and checks that need no host copy of every image.
  Status run(const Material& material, const SynthesisRequest& request,
             SynthesisTiming* timing = nullptr) noexcept;
  // Convenience: prepare, record, submit, wait, read back. `timing` may be null. `out`'s vectors are
  // resized in place: passing the same result again reuses its memory instead of faulting in new pages.
  Status synthesize(const Material& material, const SynthesisRequest& request, SynthesizedImages& out,
                    SynthesisTiming* timing = nullptr) noexcept;
  // After a synthesize() or run() with request.capture set: band (level, channel) of `subspace` over its
  // level window (row-major; rows x cols of that level's region): the noise, the CAR field y (its mean not
  // yet added) or the collapsed level G, as captured.
  Status read_band(std::uint32_t subspace, std::uint32_t level, std::uint32_t channel,
                   std::vector<float>& out, std::uint32_t& rows, std::uint32_t& cols) const noexcept;

  // Convenience after synthesize(): the interpolated image as width * height * channels floats.
  Status interpolate(const Material& material, const PairWeights& weights, std::vector<float>& out) noexcept;

  // Caps the loop iterations of one invocation (0: lavapipe's safe default). Tests lower it to
  // exercise splitting the recursion over many dispatches.
  void set_max_loop_iterations(std::uint32_t iterations) noexcept { max_loop_iterations_ = iterations; }
  // Caps the bytes of one batch's work window (0: the device's storage-buffer range). Tests lower it to
  // exercise batching.
  void set_max_batch_bytes(VkDeviceSize bytes) noexcept { max_batch_bytes_ = bytes; }
  // Caps the host buffer that synthesize() and interpolate() read back through, a band of rows at a
  // time (0: 64 MiB; at least one row). A host short of host-visible memory lowers it; tests lower it
  // to exercise several bands on a small image.
  void set_max_readback_bytes(VkDeviceSize bytes) noexcept { max_readback_bytes_ = bytes; }

 private:
  SubspaceSynthesizer() = default;
  struct Pipelines;
  struct Prepared;

  Context* context_ = nullptr;
  std::unique_ptr<Pipelines> pipelines_;
  std::unique_ptr<Prepared> prepared_;
  std::uint32_t max_loop_iterations_ = 0;
  VkDeviceSize max_batch_bytes_ = 0;
  VkDeviceSize max_readback_bytes_ = 0;
  VkDeviceSize readback_bytes() const noexcept;
};

}  // namespace carbtf
