#version 450
// One N(0,1) sample per invocation (no loops: lavapipe caps an invocation at 65,535 iterations).
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_noise.h"

layout(local_size_x = CARBTF_NOISE_GROUP_X, local_size_y = CARBTF_NOISE_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { NoiseFieldParams params; };
layout(std430, set = 0, binding = CARBTF_NOISE_BINDING_OUTPUT) writeonly buffer Output { float values[]; };

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (id.x >= params.width || id.y >= params.height) return;
  uint index = params.element_offset + id.y * params.row_pitch + id.x;
  values[index] = carbtf_gaussian(params.seed_lo, params.seed_hi, params.field_id,
                                  params.row0 + id.y, params.col0 + id.x);
}
