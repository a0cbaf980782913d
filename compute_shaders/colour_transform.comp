#version 450
// Inverse colour transform into the output layer: rgb_i = mean_i + sum_j T[i][j] G_j, summed in channel
// order from the mean. A batch may hold only some channels of an image; the next batch continues the
// sums from the stored layer, which is exact because the partial sums are float32 on both sides.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Items { ColourItemGpu items[]; };
layout(std430, set = 0, binding = 1) readonly buffer Arena { float arena[]; };
layout(set = 0, binding = 2, rgba32f) uniform image2DArray images;

void main() {
  uint i = gl_WorkGroupID.z;
  if (i >= params.item_count) return;
  uint x = gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y;
  if (x >= items[i].cols || y >= items[i].rows) return;
  ivec3 texel = ivec3(int(x), int(y), int(items[i].layer));
  uint channels = items[i].channels;
  precise vec4 acc = vec4(0.0, 0.0, 0.0, 1.0);
  if (items[i].channel_begin == 0u) {
    for (uint c = 0u; c < channels; ++c) acc[c] = items[i].mean[c];
  } else {
    acc = imageLoad(images, texel);
  }
  for (uint j = items[i].channel_begin; j < items[i].channel_end; ++j) {
    float g = arena[items[i].offset[j] + y * items[i].pitch[j] + x];
    for (uint c = 0u; c < channels; ++c) acc[c] = acc[c] + items[i].transform[c * channels + j] * g;
  }
  imageStore(images, texel, acc);
}
