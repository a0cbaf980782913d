// GPU Gaussian noise fields, the first stage of CAR synthesis: sample (row, col) of field `field_id`
// is N(0,1) computed from (seed, field_id, row, col) alone (docs/design.md 4.4), so any block of any field
// can be generated independently, and the values equal the CPU reference
// (analysis/reference/include/carbtf/reference/noise.hpp) bit for bit.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "carbtf/engine/synthesis/noise_block.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

class NoiseGenerator {
 public:
  // Builds the compute pipeline on `context`, which must outlive the generator.
  static Status create(Context& context, std::unique_ptr<NoiseGenerator>& out) noexcept;
  ~NoiseGenerator();

  // Records the dispatches that write block.width * block.height floats, row-major with a row pitch of
  // block.width, to `destination` at byte `offset` (a multiple of 4). `destination` needs
  // VK_BUFFER_USAGE_STORAGE_BUFFER_BIT. Large blocks are split across dispatches to stay within the
  // device's group-count and storage-range limits. The caller makes the shader writes visible to
  // whatever reads them next (a barrier from VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT).
  // The generator must stay alive until the command buffer has finished executing.
  Status record(VkCommandBuffer command_buffer, const NoiseBlock& block, VkBuffer destination,
                VkDeviceSize offset) const noexcept;

  // Convenience: generates `block` into `out` (resized to width * height) with submit-and-wait.
  // When `gpu_milliseconds` is given and the queue has timestamps, it receives the GPU time.
  Status generate(const NoiseBlock& block, std::vector<float>& out,
                  double* gpu_milliseconds = nullptr) noexcept;

  // Caps the rows one dispatch covers (0: only the device limits). Tests use it to exercise splitting.
  void set_max_rows_per_dispatch(std::uint32_t rows) noexcept { max_rows_per_dispatch_ = rows; }

 private:
  NoiseGenerator() = default;
  struct Pipeline;
  Context* context_ = nullptr;
  std::unique_ptr<Pipeline> pipeline_;
  std::uint32_t max_rows_per_dispatch_ = 0;
};

}  // namespace carbtf
