#version 450
// Fills every field of a batch before its recursion: the frame with zeros or stored block
// initialization values, the region with its N(0,1) noise (one sample per invocation, no loops).
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "noise.glsl"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Fields { CarFieldGpu fields[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Arena { float arena[]; };
layout(std430, set = 0, binding = 2) readonly buffer Frames { float frames[]; };

void main() {
  uint f = params.begin + gl_WorkGroupID.z;  // fields [begin, item_count): one level, one per z
  if (f >= params.item_count) return;
  uint pc = gl_GlobalInvocationID.x;
  uint pr = gl_GlobalInvocationID.y;
  uint pad = fields[f].pad;
  uint pitch = fields[f].pitch;
  uint cols = fields[f].cols;
  if (pc >= pitch || pr >= fields[f].rows + pad) return;
  float value;
  if (pr < pad || pc < pad || pc >= cols + pad) {
    uint frame = fields[f].frame_offset;
    if (frame == CARBTF_NO_FRAME) {
      value = 0.0;
    } else {
      // Stored frame: the pad rows above (pitch each), then per region row its left and right pads.
      uint side = pc < pad ? pc : pc - cols;
      uint index = pr < pad ? pr * pitch + pc : pad * pitch + (pr - pad) * 2u * pad + side;
      value = frames[frame + index];
    }
  } else {
    value = carbtf_gaussian(uvec2(params.seed_lo, params.seed_hi), fields[f].field_id, fields[f].row0 + pr - pad,
                            fields[f].col0 + pc - pad);
  }
  arena[fields[f].offset + pr * pitch + pc] = value;
}
