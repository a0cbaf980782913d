#version 450
// The 9-weight interpolation of synthesized subspace images into one (light, view) image:
// out = sum_k weight[k] * layer[k], summed from 0 in k order, terms of weight 0 skipped, as the CPU
// reference (analysis/reference/src/subspace_synthesis.cpp) does.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { InterpolateParams params; };
layout(set = 0, binding = 0, rgba32f) uniform readonly image2DArray images;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray result;

void main() {
  uint x = gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y;
  if (x >= params.width || y >= params.height) return;
  precise vec4 acc = vec4(0.0);
  for (uint k = 0u; k < 9u; ++k) {
    if (params.weight[k] == 0.0) continue;
    acc = acc + params.weight[k] * imageLoad(images, ivec3(int(x), int(y), int(params.layer[k])));
  }
  acc.w = 1.0;
  imageStore(result, ivec3(int(x), int(y), 0), acc);
}
