#version 450
// Fills every field of a batch before its recursion. By default only the frame, with zeros or the
// stored block initialization values, one invocation per frame cell in the frame's own order (pad rows
// above, then each row's left and right pads), since the recursions draw their noise themselves. With
// CARBTF_PREPARE_NOISE (conformance captures) one invocation per padded pixel, writing the frame and
// the N(0,1) noise of every region pixel. No loops.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_noise.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Fields { CarFieldGpu fields[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Arena { float arena[]; };
layout(std430, set = 0, binding = 2) readonly buffer Frames { float frames[]; };

float frame_value(uint f, uint index) {
  uint frame = fields[f].frame_offset;
  return frame == CARBTF_NO_FRAME ? 0.0 : frames[frame + index];
}

void main() {
  uint f = params.begin + gl_WorkGroupID.z;  // fields [begin, item_count): one level, one per z
  if (f >= params.item_count) return;
  uint pad = fields[f].pad;
  uint pitch = fields[f].pitch;
  uint cols = fields[f].cols;
  uint rows = fields[f].rows;
  if ((params.flags & CARBTF_PREPARE_NOISE) == 0u) {
    // Frame cell `index`, linear over x then y of the dispatch.
    uint index = gl_GlobalInvocationID.y * params.max_cols + gl_GlobalInvocationID.x;
    uint top = pad * pitch;
    if (gl_GlobalInvocationID.x >= params.max_cols || index >= top + rows * 2u * pad) return;
    uint pr, pc;
    if (index < top) {
      pr = index / pitch;
      pc = index % pitch;
    } else {
      uint side = (index - top) % (2u * pad);
      pr = pad + (index - top) / (2u * pad);
      pc = side < pad ? side : cols + side;
    }
    arena[fields[f].offset + pr * pitch + pc] = frame_value(f, index);
    return;
  }
  uint pc = gl_GlobalInvocationID.x;
  uint pr = gl_GlobalInvocationID.y;
  if (pc >= pitch || pr >= rows + pad) return;
  float value;
  if (pr < pad || pc < pad || pc >= cols + pad) {
    uint side = pc < pad ? pc : pc - cols;
    value = frame_value(f, pr < pad ? pr * pitch + pc : pad * pitch + (pr - pad) * 2u * pad + side);
  } else {
    value = carbtf_gaussian(params.seed_lo, params.seed_hi, fields[f].field_id, fields[f].row0 + pr - pad,
                            fields[f].col0 + pc - pad);
  }
  arena[fields[f].offset + pr * pitch + pc] = value;
}
