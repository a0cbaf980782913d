// Internal: the compute pipelines of the synthesis, one per kernel, the CAR kernels one per scheme and
// unrolled tap count (built when a preparation first needs one).
#pragma once

#include <cstdint>

#include "carbtf/engine/synthesis/synthesis_request.hpp"
#include "synthesis/synthesis_plan.hpp"
#include "vulkan/compute_pipeline.hpp"

namespace carbtf::detail {

struct SynthesisPipelines {
  ComputePipeline prepare;
  ComputePipeline serial[kCarTapVariants];  // [car_tap_variant()]; null until needed
  ComputePipeline wavefront[kCarTapVariants];
  ComputePipeline collapse;
  ComputePipeline colour;
  ComputePipeline colour_fold;
  ComputePipeline interpolate;

  // Every kernel but the CAR's.
  Status create(Context& context);
  // The CAR kernel of `variant`'s tap count for `scheme` (serial or wavefront), unless built already.
  Status build_car(Context& context, CarScheme scheme, std::uint32_t variant);
  const ComputePipeline& car(CarScheme scheme, std::uint32_t variant) const;
};

}  // namespace carbtf::detail
