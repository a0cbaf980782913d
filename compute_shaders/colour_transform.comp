#version 450
// Inverse colour transform into the output layer: rgb_i = mean_i + sum_j T[i][j] G_j, summed in channel
// order from the mean. A batch may hold only some channels of an image; the next batch continues the
// sums from the stored layer, which is exact because the partial sums are float32 on both sides. A
// periodic item folds each channel's G_0 first (carbtf_periodic.h).
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_periodic.h"
#include "carbtf_steps.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Items { ColourItemGpu items[]; };
layout(std430, set = 0, binding = 1) readonly buffer Arena { float arena[]; };
layout(set = 0, binding = 2, rgba32f) uniform image2DArray images;

// Adds T[c][j] * g to channel c's sum for every output channel, constant indices only (dynamic
// indexing of a vector makes lavapipe spill it to memory).
#define CARBTF_COLOUR_TERM(j)                                                                       \
  if (j >= begin && j < end) {                                                                      \
    float g = arena[offset[j] + y * pitch[j] + x];                                                  \
    if (fold) {                                                                                     \
      uint right = offset[j] + y * pitch[j] + fold_x;                                               \
      uint below = offset[j] + fold_y * pitch[j];                                                   \
      g = carbtf_fold(items[i].fold_centre[j], g, arena[right], arena[below + x], arena[below + fold_x], \
                      kx, tx, ky, ty);                                                              \
    }                                                                                               \
    acc.x = carbtf_weighted_add(acc.x, t[0u * channels + j], g);                                   \
    if (channels > 1u) acc.y = carbtf_weighted_add(acc.y, t[1u * channels + j], g);                \
    if (channels > 2u) acc.z = carbtf_weighted_add(acc.z, t[2u * channels + j], g);                \
    if (channels > 3u) acc.w = carbtf_weighted_add(acc.w, t[3u * channels + j], g);                \
  }

void main() {
  uint i = gl_WorkGroupID.z;
  if (i >= params.item_count) return;
  uint y = gl_GlobalInvocationID.y;
  if (y >= items[i].rows) return;
  uint cols = items[i].cols;
  uint channels = items[i].channels;
  uint begin = items[i].channel_begin;
  uint end = items[i].channel_end;
  int layer = int(items[i].layer);
  // The item's table entries once per invocation, for CARBTF_COLOUR_SPAN pixels (lavapipe pays per
  // workgroup and per table read).
  uint offset[CARBTF_SYNTH_MAX_CHANNELS] = items[i].offset;
  uint pitch[CARBTF_SYNTH_MAX_CHANNELS] = items[i].pitch;
  float t[CARBTF_SYNTH_MAX_CHANNELS * CARBTF_SYNTH_MAX_CHANNELS] = items[i].transform;
  vec4 start = vec4(items[i].mean[0], channels > 1u ? items[i].mean[1] : 0.0, channels > 2u ? items[i].mean[2] : 0.0,
                    channels > 3u ? items[i].mean[3] : 1.0);
  uint rows = items[i].rows;
  uint overlap = items[i].overlap;
  float inv_overlap = items[i].inv_overlap;
  // The row's fold weights and the row one period down (itself where the row is not folded).
  float ky = carbtf_fold_keep(y, overlap, inv_overlap);
  float ty = carbtf_fold_take(y, overlap, inv_overlap);
  uint fold_y = y < overlap ? y + rows : y;
  for (uint k = 0u; k < CARBTF_COLOUR_SPAN; ++k) {
    uint x = gl_GlobalInvocationID.x * CARBTF_COLOUR_SPAN + k;
    if (x >= cols) break;
    bool fold = x < overlap || y < overlap;
    float kx = carbtf_fold_keep(x, overlap, inv_overlap);
    float tx = carbtf_fold_take(x, overlap, inv_overlap);
    uint fold_x = x < overlap ? x + cols : x;
    ivec3 texel = ivec3(int(x), int(y), layer);
    precise vec4 acc = begin == 0u ? start : imageLoad(images, texel);
    CARBTF_COLOUR_TERM(0u)
    CARBTF_COLOUR_TERM(1u)
    CARBTF_COLOUR_TERM(2u)
    CARBTF_COLOUR_TERM(3u)
    imageStore(images, texel, acc);
  }
}
