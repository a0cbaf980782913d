#version 450
// CAR recursion in wavefront order, one workgroup per field: pixel (r, c) runs at step t = skew * r + c,
// so all pixels of a step are independent and the workgroup's invocations share them, with a barrier
// between steps. The scheme for GPUs. A dispatch runs steps [begin, end) of every field.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"

layout(local_size_x = CARBTF_CAR_WAVEFRONT_GROUP, local_size_y = 1, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Fields { CarFieldGpu fields[]; };
layout(std430, set = 0, binding = 1) coherent buffer Arena { float arena[]; };

#include "car.glsl"

void main() {
  uint f = params.field_begin + gl_WorkGroupID.x;
  if (f >= params.item_count) return;  // uniform across the workgroup
  CarFieldGpu field = fields[f];
  for (uint t = params.begin; t < params.end; ++t) {
    // Rows whose pixel at step t lies in [0, cols): ceil((t - cols + 1) / skew) <= r <= t / skew.
    uint first = t + 1u > field.cols ? (t + 1u - field.cols + field.skew - 1u) / field.skew : 0u;
    uint last = min(t / field.skew + 1u, field.rows);
    for (uint r = first + gl_LocalInvocationID.x; r < last; r += CARBTF_CAR_WAVEFRONT_GROUP) {
      uint c = t - field.skew * r;
      uint base = field.offset + (r + field.pad) * field.pitch + c + field.pad;
      carbtf_car_pixel(field, base, arena[base]);  // car_prepare left the pixel's noise there
    }
    memoryBarrierBuffer();
    barrier();
  }
}
