#include "synthesis/synthesis_pipelines.hpp"

#include <initializer_list>
#include <utility>

#include <carbtf_gpu_shared.h>
#include <carbtf_spirv/car_prepare.h>
#include <carbtf_spirv/car_serial.h>
#include <carbtf_spirv/car_serial_taps12.h>
#include <carbtf_spirv/car_serial_taps4.h>
#include <carbtf_spirv/car_serial_taps8.h>
#include <carbtf_spirv/car_wavefront.h>
#include <carbtf_spirv/car_wavefront_taps12.h>
#include <carbtf_spirv/car_wavefront_taps4.h>
#include <carbtf_spirv/car_wavefront_taps8.h>
#include <carbtf_spirv/collapse_level.h>
#include <carbtf_spirv/colour_fold.h>
#include <carbtf_spirv/colour_transform.h>
#include <carbtf_spirv/interpolate.h>

#include "vulkan/vk_check.hpp"

namespace carbtf::detail {
namespace {

static_assert(kCarTapVariants == 4, "one compiled kernel per tap count (compute_shaders/CMakeLists.txt)");

struct SpirvCode {
  const std::uint32_t* words;
  std::size_t bytes;
};
constexpr SpirvCode kCarSerial[kCarTapVariants] = {
    {carbtf_spirv_car_serial_taps4, sizeof(carbtf_spirv_car_serial_taps4)},
    {carbtf_spirv_car_serial_taps8, sizeof(carbtf_spirv_car_serial_taps8)},
    {carbtf_spirv_car_serial_taps12, sizeof(carbtf_spirv_car_serial_taps12)},
    {carbtf_spirv_car_serial, sizeof(carbtf_spirv_car_serial)}};
constexpr SpirvCode kCarWavefront[kCarTapVariants] = {
    {carbtf_spirv_car_wavefront_taps4, sizeof(carbtf_spirv_car_wavefront_taps4)},
    {carbtf_spirv_car_wavefront_taps8, sizeof(carbtf_spirv_car_wavefront_taps8)},
    {carbtf_spirv_car_wavefront_taps12, sizeof(carbtf_spirv_car_wavefront_taps12)},
    {carbtf_spirv_car_wavefront, sizeof(carbtf_spirv_car_wavefront)}};

Status build_pipeline(Context& context, SpirvCode code, std::uint32_t bindings, std::uint32_t push_bytes,
                      const char* name, ComputePipeline& pipeline,
                      std::initializer_list<std::pair<std::uint32_t, BindingKind>> kinds = {}) {
  ComputePipelineInfo info;
  info.spirv = code.words;
  info.spirv_bytes = code.bytes;
  info.binding_count = bindings;
  for (const auto& [binding, kind] : kinds) info.bindings[binding] = kind;
  info.push_constant_bytes = push_bytes;
  info.debug_name = name;
  return ComputePipeline::create(context, info, pipeline);
}

}  // namespace

Status SynthesisPipelines::create(Context& context) {
  constexpr std::uint32_t pass_bytes = sizeof(gpu::SynthPassParams);
  CARBTF_TRY(build_pipeline(context, {carbtf_spirv_car_prepare, sizeof(carbtf_spirv_car_prepare)}, 3,
                            pass_bytes, "carbtf car_prepare", prepare));
  CARBTF_TRY(build_pipeline(context, {carbtf_spirv_collapse_level, sizeof(carbtf_spirv_collapse_level)}, 2,
                            pass_bytes, "carbtf collapse_level", collapse));
  CARBTF_TRY(build_pipeline(context, {carbtf_spirv_colour_transform, sizeof(carbtf_spirv_colour_transform)},
                            3, pass_bytes, "carbtf colour_transform", colour,
                            {{2, BindingKind::storage_image}}));
  CARBTF_TRY(build_pipeline(context, {carbtf_spirv_colour_fold, sizeof(carbtf_spirv_colour_fold)}, 3,
                            pass_bytes, "carbtf colour_fold", colour_fold,
                            {{2, BindingKind::storage_image}}));
  CARBTF_TRY(build_pipeline(context, {carbtf_spirv_interpolate, sizeof(carbtf_spirv_interpolate)}, 2,
                            sizeof(gpu::InterpolateParams), "carbtf interpolate", interpolate,
                            {{0, BindingKind::storage_image}, {1, BindingKind::storage_image}}));
  return {};
}

Status SynthesisPipelines::build_car(Context& context, CarScheme scheme, std::uint32_t variant) {
  const bool is_serial = scheme == CarScheme::serial;
  ComputePipeline& pipeline = (is_serial ? serial : wavefront)[variant];
  if (pipeline.pipeline) return {};
  return build_pipeline(context, (is_serial ? kCarSerial : kCarWavefront)[variant], 2,
                        sizeof(gpu::SynthPassParams),
                        is_serial ? "carbtf car_serial" : "carbtf car_wavefront", pipeline);
}

const ComputePipeline& SynthesisPipelines::car(CarScheme scheme, std::uint32_t variant) const {
  return (scheme == CarScheme::serial ? serial : wavefront)[variant];
}

}  // namespace carbtf::detail
