#version 450
// N(0,1) samples of a block, four columns per invocation from one counter call: invocation x covers
// counter quad (col0 >> 2) + x, of which it writes the columns inside the block (no loops: lavapipe caps
// an invocation at 65,535 iterations).
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_noise.h"

layout(local_size_x = CARBTF_NOISE_GROUP_X, local_size_y = CARBTF_NOISE_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { NoiseFieldParams params; };
layout(std430, set = 0, binding = CARBTF_NOISE_BINDING_OUTPUT) writeonly buffer Output { float values[]; };

// Column `first + k` of the block takes sample g when it lies in the block (modulo 2^32).
#define CARBTF_PUT_NOISE(k, g) \
  if (first + k < params.width) values[row_base + first + k] = g;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (id.y >= params.height || id.x >= carbtf_noise_quads(params.col0, params.width)) return;
  uint quad = carbtf_noise_quad(params.col0, id.x);
  uint first = (quad << 2u) - params.col0;  // the quad's first column in the block, modulo 2^32
  float g0, g1, g2, g3;
  carbtf_gaussian4(params.seed_lo, params.seed_hi, params.field_id, params.row0 + id.y, quad, g0, g1, g2, g3);
  uint row_base = params.element_offset + id.y * params.row_pitch;
  CARBTF_PUT_NOISE(0u, g0) CARBTF_PUT_NOISE(1u, g1) CARBTF_PUT_NOISE(2u, g2) CARBTF_PUT_NOISE(3u, g3)
}
