#version 450
// One level of the pyramid collapse, in place: G = (mean + y) + expand(G_coarse), or mean + y for the
// coarsest level. The expand is the reference's separable one (rows first, then columns, taps
// k = -2..2 in order, weights 2 w_k); each horizontal sum is recomputed where needed instead of being
// stored, which gives the same values with no temporary field.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Items { CollapseItemGpu items[]; };
layout(std430, set = 0, binding = 1) buffer Arena { float arena[]; };

const float kExpandWeight[5] = float[5](0.125, 0.5, 0.75, 0.5, 0.125);

// Sum over the taps along a coarse row `coarse_row` (relative) for absolute fine column `col`.
float expand_along_row(in CollapseItemGpu item, int coarse_row, int col) {
  precise float acc = 0.0;
  for (int k = -2; k <= 2; ++k) {
    if (((col - k) & 1) != 0) continue;
    int j = (col - k) / 2 - int(item.coarse_col0);
    acc = acc + kExpandWeight[k + 2] * arena[item.coarse_offset + uint(coarse_row) * item.coarse_pitch + uint(j)];
  }
  return acc;
}

void main() {
  uint i = gl_WorkGroupID.z;
  if (i >= params.item_count) return;
  CollapseItemGpu item = items[i];
  uint x = gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y;
  if (x >= item.cols || y >= item.rows) return;
  uint index = item.fine_offset + y * item.fine_pitch + x;
  precise float band = item.mean + arena[index];
  if (item.coarse_offset != CARBTF_NO_FRAME) {
    int row = int(item.row0) + int(y);
    int col = int(item.col0) + int(x);
    precise float acc = 0.0;
    for (int k = -2; k <= 2; ++k) {
      if (((row - k) & 1) != 0) continue;
      int j = (row - k) / 2 - int(item.coarse_row0);
      acc = acc + kExpandWeight[k + 2] * expand_along_row(item, j, col);
    }
    band = band + acc;
  }
  arena[index] = band;
}
