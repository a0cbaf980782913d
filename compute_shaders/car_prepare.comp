#version 450
// Fills every field of a batch before its recursion. By default the frame, with zeros or the stored
// block initialization values, one invocation per frame cell in the frame's own order (pad rows above,
// then each row's left and right pads). With CARBTF_PREPARE_NOISE the N(0,1) noise of every region
// pixel, four columns per invocation (one counter call): what the wavefront recursion reads, and what a
// conformance capture of the noise stage compares. No loops.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_noise.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Fields { CarFieldGpu fields[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Arena { float arena[]; };
layout(std430, set = 0, binding = 2) readonly buffer Frames { float frames[]; };

// Column `first + k` of the region takes sample g when it lies in the region (modulo 2^32, so a quad
// straddling the region's left edge writes only its right part).
#define CARBTF_PUT_NOISE(k, g)                    \
  if (first + k < cols) arena[row_base + first + k] = g;

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
  // Noise: invocation x covers the four columns of counter quad (col0 >> 2) + x, y one region row.
  uint r = gl_GlobalInvocationID.y;
  if (r >= rows || gl_GlobalInvocationID.x >= carbtf_noise_quads(fields[f].col0, cols)) return;
  uint quad = carbtf_noise_quad(fields[f].col0, gl_GlobalInvocationID.x);
  uint first = (quad << 2u) - fields[f].col0;  // the quad's first column in the region, modulo 2^32
  float g0, g1, g2, g3;
  carbtf_gaussian4(params.seed_lo, params.seed_hi, fields[f].field_id, fields[f].row0 + r, quad, g0, g1, g2, g3);
  uint row_base = fields[f].offset + (r + pad) * pitch + pad;
  CARBTF_PUT_NOISE(0u, g0) CARBTF_PUT_NOISE(1u, g1) CARBTF_PUT_NOISE(2u, g2) CARBTF_PUT_NOISE(3u, g3)
}
