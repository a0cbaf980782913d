#version 450
// One level of the pyramid collapse, in place: G = (mean + y) + expand(G_coarse), or mean + y for the
// coarsest level. The expand is the reference's separable one (rows first, then columns, taps
// k = -2..2 in order, weights 2 w_k); each horizontal sum is recomputed where needed instead of being
// stored, which gives the same values with no temporary field. Items [begin, item_count) of the table
// (one level's bands) run in one dispatch, one item per z.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_steps.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Items { CollapseItemGpu items[]; };
layout(std430, set = 0, binding = 1) buffer Arena { float arena[]; };

// The taps of fine index i (absolute) in the reference's order k = -2..2 over the k with i - k even:
// even i reads coarse h + 1, h, h - 1 with weights 2 w = 1/8, 3/4, 1/8; odd i reads h + 1, h with 1/2,
// 1/2, and a third tap of weight 0 (adding +0 or -0 to a sum that starts from +0 changes no bit), so
// neighbouring lanes of either parity run the same instructions.
struct Taps {
  ivec3 index;
  vec3 weight;
};

Taps expand_taps(int i) {
  int h = i >> 1;  // floor(i / 2), also for negative i
  bool even = (i & 1) == 0;
  Taps t;
  t.index = ivec3(h + 1, h, even ? h - 1 : h);
  t.weight = even ? vec3(0.125, 0.75, 0.125) : vec3(0.5, 0.5, 0.0);
  return t;
}

void main() {
  uint i = params.begin + gl_WorkGroupID.z;
  if (i >= params.item_count) return;
  uint y = gl_GlobalInvocationID.y;
  if (y >= items[i].rows) return;
  uint cols = items[i].cols;
  uint fine_offset = items[i].fine_offset;
  uint coarse_offset = items[i].coarse_offset;
  uint pitch = items[i].coarse_pitch;
  Taps rows = expand_taps(int(items[i].row0) + int(y));
  ivec3 r = rows.index - int(items[i].coarse_row0);
  // CARBTF_COLLAPSE_SPAN consecutive pixels per invocation: lavapipe pays per workgroup and per table read.
  for (uint k = 0u; k < CARBTF_COLLAPSE_SPAN; ++k) {
    uint x = gl_GlobalInvocationID.x * CARBTF_COLLAPSE_SPAN + k;
    if (x >= cols) break;
    uint index = fine_offset + y * items[i].fine_pitch + x;
    precise float band = items[i].mean + arena[index];
    if (coarse_offset != CARBTF_NO_FRAME) {
      Taps taps = expand_taps(int(items[i].col0) + int(x));
      ivec3 c = taps.index - int(items[i].coarse_col0);
      precise float acc = 0.0;
      for (int t = 0; t < 3; ++t) {
        uint row_start = coarse_offset + uint(r[t]) * pitch;
        precise float along_row = 0.0;
        along_row = carbtf_weighted_add(along_row, taps.weight.x, arena[row_start + uint(c.x)]);
        along_row = carbtf_weighted_add(along_row, taps.weight.y, arena[row_start + uint(c.y)]);
        along_row = carbtf_weighted_add(along_row, taps.weight.z, arena[row_start + uint(c.z)]);
        acc = carbtf_weighted_add(acc, rows.weight[t], along_row);
      }
      band = band + acc;
    }
    arena[index] = band;
  }
}
