// Internal: the host-side plan of a GPU subspace synthesis. Lays out every CAR field (subspace x level x
// channel) of a request in batches whose work window fits one storage-buffer binding, and fills the
// item tables the kernels read (carbtf_gpu_shared.h). No Vulkan calls, so it is cheap to test.
#pragma once

#include <cstdint>
#include <vector>

#include <carbtf_gpu_shared.h>

#include "carbtf/engine/internal/synthesis_layout.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/status.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"

namespace carbtf::detail {

// Where one field lies: which band, and its place in the batch window (gpu.offset and friends).
struct PlannedField {
  std::uint32_t subspace = 0;
  std::uint32_t level = 0;
  std::uint32_t channel = 0;
  TextureRegion window;  // the level window the collapse uses (absolute coordinates)
  gpu::CarFieldGpu gpu{};
  std::uint32_t window_element() const noexcept;  // window (0, 0) in the batch window
  std::uint32_t steps() const noexcept;           // wavefront steps: skew * (rows - 1) + cols
};

// The fields of one pyramid level within a batch (consecutive in PlannedBatch::fields): dispatch grids
// sized per level leave no mostly-empty workgroups for the smaller levels.
struct LevelGroup {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  std::uint32_t max_padded_rows = 0;
  std::uint32_t max_pitch = 0;
  std::uint32_t max_window_rows = 0;
  std::uint32_t max_window_cols = 0;
  std::uint32_t max_frame_cells = 0;  // car_frame_floats() of the largest field
};

// The CAR kernels unroll 4, 8, 12 or 16 taps (compute_shaders/include/car.glsl): variant v unrolls
// 4 (v + 1), and a field of n neighbours needs variant car_tap_variant(n).
inline constexpr std::uint32_t kCarTapStep = 4;
inline constexpr std::uint32_t kCarTapVariants = gpu::CARBTF_CAR_MAX_NEIGHBOURS / kCarTapStep;
constexpr std::uint32_t car_tap_variant(std::uint32_t neighbours) {
  return (neighbours > 0 ? neighbours + kCarTapStep - 1 : kCarTapStep) / kCarTapStep - 1;
}

// Consecutive fields of one level that one CAR kernel variant runs in one dispatch series: within a
// level the fields are ordered by variant, so that a 1-neighbour field does not run 12 masked taps
// beside a 12-neighbour one.
struct CarRun {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  std::uint32_t tap_variant = 0;
  std::uint64_t max_region_quads = 0;  // serial iterations: rows x counter quads per row
  std::uint32_t max_region_rows = 0;
  std::uint32_t max_steps = 0;  // wavefront steps
};

struct PlannedBatch {
  std::vector<LevelGroup> levels;                           // [level]
  std::vector<CarRun> car_runs;                             // in field order
  std::vector<PlannedField> fields;                         // level 0 of every stack first, then level 1, ...
                                                            // each level's fields ordered by tap variant
  std::vector<std::vector<gpu::CollapseItemGpu>> collapse;  // [level]: the items collapsing that level
  std::vector<gpu::ColourItemGpu> colour;
  std::uint64_t window_floats = 0;
};

struct SynthesisPlan {
  std::vector<std::uint32_t> subspaces;  // one per output layer
  std::vector<std::uint32_t> channels;   // per output layer
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t periodic_overlap = 0;
  std::vector<PlannedBatch> batches;
  std::uint64_t window_floats = 0;  // the largest batch window
};

// Plans `request` over `material` with batch windows of at most `max_window_bytes`. invalid_argument
// (naming the cause) for a request the GPU path cannot serve. With request.initial_values, every field's
// frame_offset points into them (block_frame_layout()).
Status plan_synthesis(const Material& material, const SynthesisRequest& request,
                      std::uint64_t max_window_bytes, SynthesisPlan& out);

}  // namespace carbtf::detail
