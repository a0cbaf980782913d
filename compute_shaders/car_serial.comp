#version 450
// CAR recursion, one invocation per field, pixels in row-major order: the scheme for CPU devices
// (lavapipe), where barriers cost more than the lost parallelism inside a field (docs/design.md 6). A
// dispatch runs the linear pixels [begin, end) of every field, so that no invocation loops more than
// lavapipe's 65,535 times; successive dispatches continue where the last stopped.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"

layout(local_size_x = CARBTF_CAR_SERIAL_GROUP, local_size_y = 1, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Fields { CarFieldGpu fields[]; };
layout(std430, set = 0, binding = 1) buffer Arena { float arena[]; };

#include "car.glsl"

void main() {
  uint f = gl_GlobalInvocationID.x;
  if (f >= params.item_count) return;
  CarFieldGpu field = fields[f];
  uint end = min(params.end, field.rows * field.cols);
  if (params.begin >= end) return;
  uint r = params.begin / field.cols;
  uint c = params.begin % field.cols;
  uint base = field.offset + (r + field.pad) * field.pitch + c + field.pad;
  for (uint i = params.begin; i < end; ++i) {
    carbtf_car_pixel(field, base, r, c);
    ++c;
    ++base;
    if (c == field.cols) {
      c = 0u;
      ++r;
      base += 2u * field.pad;
    }
  }
}
