#version 450
// CAR recursion, one invocation per field, pixels in row-major order: the scheme for CPU devices
// (lavapipe), where barriers cost more than the lost parallelism inside a field (docs/design.md 6). A
// dispatch runs iterations [begin, end) of every field, one per counter quad of a row (row-major), so
// that no invocation loops more than lavapipe's 65,535 times; successive dispatches continue where the
// last stopped.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_noise.h"

layout(local_size_x = CARBTF_CAR_SERIAL_GROUP, local_size_y = 1, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Fields { CarFieldGpu fields[]; };
layout(std430, set = 0, binding = 1) buffer Arena { float arena[]; };

#include "car.glsl"

// Region column `first + k` of the row takes the CAR step with noise g when it lies in the region
// (modulo 2^32: a quad straddling the left edge steps only its right part).
#define CARBTF_SERIAL_STEP(k, g) \
  if (first + k < field.cols) carbtf_car_pixel(field, row_base + first + k, g);

void main() {
  uint f = params.field_begin + gl_GlobalInvocationID.x;
  if (f >= params.item_count) return;
  CarFieldGpu field = fields[f];
  // One iteration per counter quad of a row, four pixels from one counter call (carbtf_noise.h): every
  // invocation draws at the same iterations, so the invocations sharing SIMD lanes never wait for each
  // other's draws, whatever their fields' column alignment.
  uint quads = carbtf_noise_quads(field.col0, field.cols);
  uint end = min(params.end, field.rows * quads);
  if (params.begin >= end) return;
  uint r = params.begin / quads;
  uint q = params.begin % quads;
  for (uint i = params.begin; i < end; ++i) {
    uint quad = carbtf_noise_quad(field.col0, q);
    uint first = (quad << 2u) - field.col0;  // the quad's first column in the region, modulo 2^32
    uint row_base = field.offset + (r + field.pad) * field.pitch + field.pad;
    float g0, g1, g2, g3;
    carbtf_gaussian4(params.seed_lo, params.seed_hi, field.field_id, field.row0 + r, quad, g0, g1, g2, g3);
    CARBTF_SERIAL_STEP(0u, g0) CARBTF_SERIAL_STEP(1u, g1) CARBTF_SERIAL_STEP(2u, g2) CARBTF_SERIAL_STEP(3u, g3)
    ++q;
    if (q == quads) {
      q = 0u;
      ++r;
    }
  }
}
