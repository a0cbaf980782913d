// Constants and buffer layouts shared by GLSL and C++. Included by shaders as "carbtf_gpu_shared.h" and
// by C++ as <carbtf_gpu_shared.h>; the C++ side checks every layout with static_assert, so a change
// here that breaks the agreement fails to compile instead of producing garbage on the GPU.
#ifndef CARBTF_GPU_SHARED_H
#define CARBTF_GPU_SHARED_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace carbtf::gpu {
using uint = std::uint32_t;
#define CARBTF_CONST_FLOAT(name, value) inline constexpr float name = value;
#define CARBTF_CONST_UINT(name, value) inline constexpr uint name = value;
#define CARBTF_FUNCTION inline constexpr
#else
#define CARBTF_FUNCTION
#define CARBTF_CONST_FLOAT(name, value) const float name = value;
#define CARBTF_CONST_UINT(name, value) const uint name = value;
#endif

// ---- Gaussian noise (docs/design.md 4.4) -------------------------------------------------------------
// N(0,1) at (seed, field id, row, col). Four columns share one counter call: Philox4x32-10 of counter
// (col >> 2, row, field, 0) under key (seed low, seed high) gives four 32-bit words w0..w3, and their top
// 24 bits make two Box-Muller pairs: u1 = (w0 >> 8) + 1, u2 = w1 >> 8, u3 = (w2 >> 8) + 1, u4 = w3 >> 8
// (times 2^-24). Column col & 3 takes, in order, sqrt(-2 ln u1) cos(2 pi u2), sqrt(-2 ln u1) sin(2 pi u2),
// then the same of (u3, u4); sin(2 pi u) is cos(2 pi (u - 1/4)), the shift done on the 24-bit integer so
// that it is exact. ln, cos and sqrt are built from correctly rounded +, -, * only (Vulkan guarantees
// nothing more), so float32 results agree bit for bit.
// The counter quads a row of `cols` columns from column col0 touches: one invocation each where a
// dispatch fills noise.
CARBTF_FUNCTION uint carbtf_noise_quads(uint col0, uint cols) {
  return ((col0 & 3u) + cols + 3u) >> 2u;
}
// The counter quad that is the j-th a row from column col0 touches (quads taken modulo 2^30, as columns
// are modulo 2^32); its column 0 lies at (quad << 2) - col0 of the row, modulo 2^32.
CARBTF_FUNCTION uint carbtf_noise_quad(uint col0, uint j) {
  return ((col0 >> 2u) + j) & 0x3FFFFFFFu;
}
CARBTF_CONST_UINT(CARBTF_PHILOX_M0, 0xD2511F53u)
CARBTF_CONST_UINT(CARBTF_PHILOX_M1, 0xCD9E8D57u)
CARBTF_CONST_UINT(CARBTF_PHILOX_W0, 0x9E3779B9u)
CARBTF_CONST_UINT(CARBTF_PHILOX_W1, 0xBB67AE85u)
CARBTF_CONST_UINT(CARBTF_PHILOX_ROUNDS, 10u)
CARBTF_CONST_FLOAT(CARBTF_TWO_POW_MINUS_24, 5.9604644775390625e-08f)
CARBTF_CONST_FLOAT(CARBTF_LN2, 6.931471806e-01f)
CARBTF_CONST_FLOAT(CARBTF_SQRT2, 1.414213538e+00f)
CARBTF_CONST_UINT(CARBTF_RSQRT_MAGIC, 0x5F3759DFu)
// Polynomials from scripts/gen_noise_polynomials.py (Chebyshev interpolants, float32 coefficients):
// ln(1+x) = x * sum_{k>=1} C_k x^(k-1), x in [sqrt(1/2)-1, sqrt(2)-1], max abs error 6.3e-10;
// cos(2 pi r) = sum_k C_k (r^2)^k, r in [0, 1/4], max abs error 2.9e-08.
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C1, 1.000000000e+00f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C2, -5.000000000e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C3, 3.333333433e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C4, -2.499998212e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C5, 1.999981105e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C6, -1.666736603e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C7, 1.429283023e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C8, -1.249126047e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C9, 1.098139361e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C10, -9.961545467e-02f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C11, 1.017364264e-01f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C12, -9.827125072e-02f)
CARBTF_CONST_FLOAT(CARBTF_LOG1P_C13, 5.083188415e-02f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C0, 1.000000000e+00f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C1, -1.973920822e+01f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C2, 6.493939209e+01f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C3, -8.545681763e+01f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C4, 6.024462891e+01f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C5, -2.642589378e+01f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C6, 7.896629333e+00f)
CARBTF_CONST_FLOAT(CARBTF_COS2PI_C7, -1.645584106e+00f)

// ---- noise_field.comp ---------------------------------------------------------------------------
CARBTF_CONST_UINT(CARBTF_NOISE_GROUP_X, 16u)
CARBTF_CONST_UINT(CARBTF_NOISE_GROUP_Y, 16u)
CARBTF_CONST_UINT(CARBTF_NOISE_BINDING_OUTPUT, 0u)

// Push constants of noise_field.comp: writes the block rows [row0, row0+height) x cols
// [col0, col0+width) of field `field_id` to output[element_offset + r * row_pitch + c].
struct NoiseFieldParams {
  uint seed_lo;
  uint seed_hi;
  uint field_id;
  uint row0;  // two's complement: a block may start above row 0 (burn-in margins)
  uint col0;
  uint width;
  uint height;
  uint row_pitch;       // in floats
  uint element_offset;  // in floats, from the start of the bound range
};

// ---- Subspace-image synthesis (engine/src/subspace_synthesizer.cpp) ---------------------------
// Every pass reads a table of items from binding 0 and works on one arena window (binding 1) that
// holds the batch's CAR fields. A field is stored padded: `pad` frame rows above its region and `pad`
// frame columns each side, row pitch cols + 2 pad; region pixel (r, c) is arena[offset + (r + pad) *
// pitch + c + pad]. The frame holds zeros (a burn-in start) or stored block-initialization values.
CARBTF_CONST_UINT(CARBTF_CAR_MAX_NEIGHBOURS, 16u)
CARBTF_CONST_UINT(CARBTF_SYNTH_MAX_CHANNELS, 4u)
CARBTF_CONST_UINT(CARBTF_SYNTH_GROUP_X, 16u)
CARBTF_CONST_UINT(CARBTF_SYNTH_GROUP_Y, 16u)
CARBTF_CONST_UINT(CARBTF_COLOUR_SPAN, 32u)  // pixels of a row per invocation of colour_transform.comp
CARBTF_CONST_UINT(CARBTF_COLLAPSE_SPAN,
                  16u)  // 2 x 2 blocks of a block row per invocation of collapse_level.comp
CARBTF_CONST_UINT(CARBTF_FOLD_GROUP, 64u)           // fold texels per workgroup of colour_fold.comp
CARBTF_CONST_UINT(CARBTF_CAR_SERIAL_GROUP, 8u)      // fields per workgroup of car_serial.comp
CARBTF_CONST_UINT(CARBTF_CAR_WAVEFRONT_GROUP, 64u)  // invocations per field in car_wavefront.comp
CARBTF_CONST_UINT(CARBTF_NO_FRAME, 0xFFFFFFFFu)     // CarFieldGpu.frame_offset: the frame is zero
// car_prepare writes the frame only (one invocation per frame cell, the recursions draw their noise
// themselves), or with this flag also the noise of every region pixel, for conformance captures.
CARBTF_CONST_UINT(CARBTF_PREPARE_NOISE, 1u)

struct CarFieldGpu {
  uint offset;  // arena element of padded (0, 0)
  uint pitch;   // cols + 2 pad
  uint rows;    // region rows (burn-in margin included)
  uint cols;    // region columns (margins included)
  uint pad;
  uint field_id;
  uint row0;  // absolute row of region pixel (0, 0), two's complement (noise coordinates)
  uint col0;
  uint neighbour_count;
  uint skew;          // wavefront: pixel (r, c) runs at step skew * r + c
  uint frame_offset;  // element of the stored frame in the frame buffer, or CARBTF_NO_FRAME
  float sigma;
  int tap[CARBTF_CAR_MAX_NEIGHBOURS];  // dr * pitch + dc
  float gamma[CARBTF_CAR_MAX_NEIGHBOURS];
};

// One band of one level: G = (mean + y) + expand(G_coarse), written over y in the level window.
struct CollapseItemGpu {
  uint fine_offset;  // arena element of the level window's (0, 0)
  uint fine_pitch;
  uint rows;  // level window
  uint cols;
  uint row0;  // absolute coordinates of the level window (two's complement)
  uint col0;
  uint coarse_offset;  // arena element of the coarse level window's (0, 0), or CARBTF_NO_FRAME: none
  uint coarse_pitch;
  uint coarse_row0;
  uint coarse_col0;
  float mean;
  uint reserved;
};

// The colour transform of channels [channel_begin, channel_end) of one subspace image: from the mean
// when channel_begin is 0, else continuing the sums already in the output layer. With overlap > 0 the
// output is periodic: each channel's G_0 is folded first (carbtf_periodic.h), rows x cols being the
// period and the G_0 window (rows + overlap) x (cols + overlap).
struct ColourItemGpu {
  uint layer;
  uint channels;
  uint channel_begin;
  uint channel_end;
  uint rows;
  uint cols;
  uint overlap;
  float inv_overlap;                       // 1 / overlap, rounded on the host
  uint offset[CARBTF_SYNTH_MAX_CHANNELS];  // arena element of each channel's G_0 (0, 0)
  uint pitch[CARBTF_SYNTH_MAX_CHANNELS];
  float mean[CARBTF_SYNTH_MAX_CHANNELS];
  float fold_centre[CARBTF_SYNTH_MAX_CHANNELS];  // collapsed_band_mean() per channel
  float transform[CARBTF_SYNTH_MAX_CHANNELS * CARBTF_SYNTH_MAX_CHANNELS];  // row-major, channels x channels
};

struct SynthPassParams {
  uint item_count;
  uint seed_lo;
  uint seed_hi;
  uint begin;  // car_serial: first linear pixel; car_wavefront: first step
  uint end;
  uint max_rows;
  uint max_cols;
  uint flags;        // car_prepare: CARBTF_PREPARE_* bits
  uint field_begin;  // car_serial, car_wavefront: the first field of the run; item_count is its end
};

// interpolate.comp: out = sum_k weight[k] * layer[k], k = 0..8 in order, terms of weight 0 skipped.
struct InterpolateParams {
  uint layer[12];  // 9 used; std430 array of 12 keeps the float array 16-byte aligned for std140 readers
  float weight[12];
  uint width;
  uint height;
  uint channels;
  uint reserved;
};

// ---- Range-map tile layout (engine/include/carbtf/engine/material/range_tiles.hpp) ----------------------
// A 32-bit integer mixer ("lowbias32", C. Wellons): every output bit depends on every input bit.
// Integer arithmetic only, so C++ and GLSL agree exactly.
CARBTF_FUNCTION uint carbtf_hash32(uint x) {
  x ^= x >> 16u;
  x *= 0x7FEB352Du;
  x ^= x >> 15u;
  x *= 0x846CA68Bu;
  x ^= x >> 16u;
  return x;
}

// The colour of one tile edge: `kind` 0 for the horizontal edge above tile (row, col), 1 for the
// vertical edge left of it; rows and columns are two's complement.
CARBTF_FUNCTION uint carbtf_tile_edge_colour(uint seed_lo, uint seed_hi, uint kind, uint row, uint col,
                                             uint colours) {
  uint h = carbtf_hash32(
      col ^ carbtf_hash32(row ^ carbtf_hash32(kind ^ carbtf_hash32(seed_lo ^ carbtf_hash32(seed_hi)))));
  return h % colours;
}

// ---- Direction angles (render pass, scene pruning) -------------------------------------------
// atan(t) = t * sum_k C_k (t^2)^k, t in [0, 1], max abs error 3.0e-09 (scripts/gen_noise_polynomials.py).
// Vulkan allows atan 4096 ULP of error, which moves interpolation weights by 1e-3; this keeps the GPU
// within about 1e-7 of the CPU, so that scene pruning predicts the fragment stage's directions.
CARBTF_CONST_FLOAT(CARBTF_ATAN_C0, 1.000000000e+00f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C1, -3.333332241e-01f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C2, 1.999955773e-01f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C3, -1.427857578e-01f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C4, 1.105077118e-01f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C5, -8.785042912e-02f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C6, 6.685281545e-02f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C7, -4.392841086e-02f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C8, 2.191294543e-02f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C9, -7.030669134e-03f)
CARBTF_CONST_FLOAT(CARBTF_ATAN_C10, 1.057607355e-03f)
CARBTF_CONST_FLOAT(CARBTF_HALF_PI, 1.570796327e+00f)
CARBTF_CONST_FLOAT(CARBTF_PI_F, 3.141592654e+00f)

// The polar angle, in [0, pi], of a direction whose horizontal part has length r >= 0 and whose
// vertical part is z: atan2(r, z) from +, -, * and / only.
CARBTF_FUNCTION float carbtf_polar_angle(float r, float z) {
  float h = z < 0.0f ? -z : z;
  bool steep = r > h;
  float t = steep ? h / r : (h > 0.0f ? r / h : 0.0f);
  float s = t * t;
  float p = CARBTF_ATAN_C10;
  p = p * s + CARBTF_ATAN_C9;
  p = p * s + CARBTF_ATAN_C8;
  p = p * s + CARBTF_ATAN_C7;
  p = p * s + CARBTF_ATAN_C6;
  p = p * s + CARBTF_ATAN_C5;
  p = p * s + CARBTF_ATAN_C4;
  p = p * s + CARBTF_ATAN_C3;
  p = p * s + CARBTF_ATAN_C2;
  p = p * s + CARBTF_ATAN_C1;
  p = p * s + CARBTF_ATAN_C0;
  float a = t * p;
  float from_z = steep ? CARBTF_HALF_PI - a : a;
  return z < 0.0f ? CARBTF_PI_F - from_z : from_z;
}

// ---- Material render pass (carbtf_material.glsl, engine/include/carbtf/engine/render/material_binding.hpp)
// -- The material descriptor set: binding 0 the subspace images (sampler2DArray, one layer per synthesized
// subspace image), binding 1 the enlarged range map (sampler2DArray: layer 0 r the heights in texels and gba
// each colour channel's relief tone, layer 1 rgb the relief normal and a its length, layers 2 and 3 the
// horizons of azimuths 0-3 and 4-7 for cast shadows), binding 2 the lookup tables (readonly
// storage buffer: MaterialTablesHeader, then the tables), binding 3 the same buffer as RGBA32UI texels
// (usamplerBuffer: 16-byte "quads"), through which the fragment stage reads the tables after the header.
// The subspace images have MaterialTablesHeader::mip_levels levels, the range map relief_levels:
// relief_chroma_levels more where the texture's size allows it, for the relief's chroma
// (carbtf_material_shade()).
CARBTF_CONST_UINT(CARBTF_MATERIAL_BINDING_SUBSPACES, 0u)
CARBTF_CONST_UINT(CARBTF_MATERIAL_BINDING_RANGE, 1u)
CARBTF_CONST_UINT(CARBTF_MATERIAL_BINDING_TABLES, 2u)
CARBTF_CONST_UINT(CARBTF_MATERIAL_BINDING_TABLE_QUADS, 3u)
// A (light, view) pair whose subspace image was not synthesized.
CARBTF_CONST_UINT(CARBTF_NO_LAYER, 0xFFFFFFFFu)
// The same in MaterialTablesHeader::pair_table's 16-bit layer field; layers stop below it.
CARBTF_CONST_UINT(CARBTF_PAIR_NO_LAYER, 0xFFFFu)
// A pair gain in the pair table (MaterialTablesHeader::pair_table) is a 10-bit count of these fractions
// (gains 1/4 to 4).
CARBTF_CONST_FLOAT(CARBTF_PAIR_GAIN_UNITS, 256.0f)
// A lookup-cell entry with this bit is a boundary edge, else a triangle.
CARBTF_CONST_UINT(CARBTF_LOOKUP_EDGE_BIT, 0x80000000u)
CARBTF_CONST_UINT(CARBTF_LOOKUP_ENTRY_QUADS, 3u)
// A fragment inside a triangle up to this barycentric slack uses it; further out, the nearest edge.
CARBTF_CONST_FLOAT(CARBTF_LOOKUP_INSIDE_SLACK, 1.0e-5f)
// Direction weights below this are dropped (and the rest renormalised), so that a fragment at or next
// to a measured direction uses exactly the directions it is nearest, whichever of two triangles that
// share an edge its rounding picks; scene pruning relies on it.
CARBTF_CONST_FLOAT(CARBTF_LOOKUP_MIN_WEIGHT, 1.0e-5f)
// The constant id of carbtf_material.glsl's specialization constant that compiles the cast shadows in
// (its default) or out, unless the including shader defines CARBTF_SHADOWS_CONSTANT_ID (a macro: a
// layout qualifier takes a literal).
#define CARBTF_SHADOWS_DEFAULT_CONSTANT_ID 1000
// The constant id of carbtf_material.glsl's specialization constant that reads the subspace images and
// the range texture's heights, tone and horizons through the sampler's trilinear filtering instead of
// by hand, unless the including shader defines CARBTF_HARDWARE_FILTERING_CONSTANT_ID.
#define CARBTF_HARDWARE_FILTERING_DEFAULT_CONSTANT_ID 1001
// The constant id of carbtf_material.glsl's cost probe (`carbtf bench frame --parts`): 0, the default,
// draws the material; each bit below replaces one part of the fragment stage by a constant, so that a
// benchmark measures the render pass without it. The picture is then wrong: for timing only.
#define CARBTF_COST_PROBE_DEFAULT_CONSTANT_ID 1002
CARBTF_CONST_UINT(CARBTF_COST_PROBE_LOOKUPS, 1u)         // the two direction lookups: fixed weights
CARBTF_CONST_UINT(CARBTF_COST_PROBE_PAIR_READS, 2u)      // the pair table: layers from the indices
CARBTF_CONST_UINT(CARBTF_COST_PROBE_SUBSPACE_READS, 4u)  // the 9 subspace image reads: the layer's grey
CARBTF_CONST_UINT(CARBTF_COST_PROBE_RELIEF, 8u)          // the normal, tone and horizons: flat, 1, none
CARBTF_CONST_UINT(CARBTF_COST_PROBE_PARALLAX, 16u)       // the parallax height reads: no shift
// The parallax ray march (carbtf_parallax_uv, and its CPU twin): a step moves the ray at most this many
// texels across or down (the sample renderer's, height_field_renderer.cpp), MaterialTablesHeader::
// parallax_steps at most, longer ones where that many do not reach; then bisections between the last
// point above the relief and the first below, and the chord between them. Views nearer grazing than this
// cosine march as at it: the ray's reach stays finite.
CARBTF_CONST_FLOAT(CARBTF_PARALLAX_STEP_TEXELS, 0.5f)
CARBTF_CONST_UINT(CARBTF_PARALLAX_REFINEMENTS, 4u)
CARBTF_CONST_FLOAT(CARBTF_PARALLAX_MIN_VIEW_Z, 0.05f)
// The constant id of carbtf_material.glsl's specialization constant that picks how the light's and the
// view's 3 weights combine into weights of (light, view) pairs (PairCoupling, direction_interpolation.hpp):
// CARBTF_PAIR_COUPLING_PRODUCT, the default, reads 9 pairs; CARBTF_PAIR_COUPLING_STAIRCASE at most 5.
#define CARBTF_PAIR_COUPLING_DEFAULT_CONSTANT_ID 1003
CARBTF_CONST_UINT(CARBTF_PAIR_COUPLING_PRODUCT, 0u)
CARBTF_CONST_UINT(CARBTF_PAIR_COUPLING_STAIRCASE, 1u)
// The staircase coupling: the light's 3 weights and the view's, each in ascending order of direction
// index, laid end to end on [0, 1]; a pair gets the length its light's and its view's intervals share.
// Walked from the first light and view to the third of each, one pair per step, 5 steps: a step takes
// what both current intervals still hold, then moves on to the next light where the light's interval
// ends first (or the views are done), else to the next view.
CARBTF_CONST_UINT(CARBTF_STAIRCASE_STEPS, 5u)
CARBTF_FUNCTION bool carbtf_staircase_next_is_light(float light_left, float view_left, uint light_step,
                                                    uint view_step) {
  return (light_left < view_left && light_step < 2u) || view_step == 2u;
}
// The penumbra of the relief's cast shadows, in tangent of elevation (relief_horizons.hpp).
CARBTF_CONST_FLOAT(CARBTF_RELIEF_SHADOW_SOFTNESS, 0.1f)
// The relief's ambient share of the relit factor (kReliefAmbient, material.hpp).
CARBTF_CONST_FLOAT(CARBTF_RELIEF_AMBIENT, 0.1f)
// The view's z below which the specular lobe grows no more (kSpecularViewFloor, material.hpp).
CARBTF_CONST_FLOAT(CARBTF_SPECULAR_VIEW_FLOOR, 0.25f)
// The relief's chroma is mixed in values encoded about as a camera stores them (sRGB's exponent), by
// Rec. 601's luma weights, JPEG's YCbCr (carbtf_material_shade(), relief_chroma_mix()).
CARBTF_CONST_FLOAT(CARBTF_CHROMA_GAMMA, 1.0f / 2.4f)
CARBTF_CONST_FLOAT(CARBTF_LUMA_RED, 0.299f)
CARBTF_CONST_FLOAT(CARBTF_LUMA_GREEN, 0.587f)
CARBTF_CONST_FLOAT(CARBTF_LUMA_BLUE, 0.114f)
// Lights one draw of carbtf's own mesh pipeline shades with.
CARBTF_CONST_UINT(CARBTF_RENDER_MAX_LIGHTS, 4u)

// One direction set's lookup (engine/internal/carbtf/engine/internal/direction_lookup.hpp): a grid of
// grid_size^2 cells over the projected disk [-1, 1]^2, row y, column x. Offsets count quads (16 bytes)
// from the start of the buffer. Cell c lists entries [begin, end): the words 2c and 2c + 1 from quad
// `cells` on. Each entry is CARBTF_LOOKUP_ENTRY_QUADS quads holding all a fragment needs, so that it
// reads them after one indirection, not three (entry, then triangle, then points: fetches that wait on
// each other):
//   a triangle: i0, i1, i2 (direction indices), 0, then the projections of i0, i1, i2 (x, y as uint
//   bits), 0, 0;
//   a boundary edge: CARBTF_LOOKUP_EDGE_BIT | i0, i1, i1, 0, then the projections of i0, i1, i1, 0, 0.
struct DirectionLookupGpu {
  uint count;      // directions
  uint grid_size;  // cells per side
  uint cells;      // quad of the grid_size^2 (begin, end) word pairs
  uint entries;    // quad of the first entry, CARBTF_LOOKUP_ENTRY_QUADS quads each
  uint reserved0;
  uint reserved1;
  uint reserved2;
  uint reserved3;
};

struct MaterialTablesHeader {
  DirectionLookupGpu lights;
  DirectionLookupGpu views;
  uint pair_table;  // quad of lights * views word pairs, [light * views + view]: first the pair's texture
                    // layer in the low 16 bits (CARBTF_PAIR_NO_LAYER where it was not synthesized) and
                    // its subspace's tone weight (SubspaceModel::tone_weight) as a half float in the
                    // high 16; then its gains on R, G and B (Material::pair_gains; 1 without) in bits
                    // 0-9, 10-19 and 20-29, in units of 1/CARBTF_PAIR_GAIN_UNITS: one fetch per tap
  uint width;       // texels of the subspace images and of the range map
  uint height;
  uint pair_gains;       // 1: the material has pair gains (the pair table holds them); 0: it has none
  float parallax_scale;  // parallax offset in texels = parallax_scale * (height - range_mean) * view.xy
  float range_mean;
  float light_z_floor;  // cos of the largest measured light elevation: the relit factor's denominator floor
  uint wrap;            // 1: the textures tile, texel addresses wrap; 0: edge texels repeat
  uint shadows;         // 1: the relief casts shadows (the range texture's layers 2 and 3 hold its horizons)
  float specular_strength;  // the relief's specular lobe (RangeTiles::specular_strength; 0: none)
  float specular_gloss;
  uint mip_levels;  // levels of the subspace images, level 0 included (mip_chain.hpp)
  // The parallax ray march (carbtf_parallax_uv): the highest and lowest point of the relief, parallax_scale
  // * (height - range_mean) in texels, and the most steps it takes down the ray (0: offset mapping, one
  // height read).
  float parallax_top;
  float parallax_bottom;
  uint parallax_steps;
  // Levels of the range map: mip_levels + relief_chroma_levels where its size allows it (and the device can
  // filter it), so that the relief's chroma can be read that many levels above its brightness.
  uint relief_levels;
  uint tone_planes;  // the relief tone's planes (tone_planes() of material.hpp): 0 none, 1 grey, 3 R, G, B
  // How many mip levels above its brightness the relief's chroma is read (RangeTiles::chroma_levels): the
  // measured images' own colour resolution.
  uint relief_chroma_levels;
  float specular_view_power;  // the lobe's growth with the view's tilt (RangeTiles::specular_view_power)
  uint reserved2;
};

#ifdef __cplusplus
// C++ stand-ins of the GLSL types the uniform block below uses, with their std140 size and alignment
// (16 bytes), so that the block has one definition for both languages.
struct alignas(16) vec4 {
  float x, y, z, w;
};
struct alignas(16) uvec4 {
  uint x, y, z, w;
};
struct alignas(16) mat4 {
  float columns[16];  // column-major, as GLSL's
};
#endif

// carbtf's own mesh pipeline (material_vertex.vert / material_fragment.frag): per-draw uniforms, std140.
struct RenderFrameUniforms {
  mat4 view_projection;  // world -> clip
  mat4 model;            // object -> world (rotation, translation, uniform scale)
  vec4 camera;           // w = 1: camera position; w = 0: direction towards an orthographic camera
  vec4 light_position[CARBTF_RENDER_MAX_LIGHTS];  // w = 1: point light; w = 0: direction to the light
  vec4 light_colour[CARBTF_RENDER_MAX_LIGHTS];    // linear RGB scale (point lights: at distance 1)
  uvec4 counts;                                   // x: light count
};

#ifdef __cplusplus
static_assert(sizeof(NoiseFieldParams) == 36, "NoiseFieldParams must match the GLSL push-constant layout");
static_assert(offsetof(NoiseFieldParams, row0) == 12);
static_assert(offsetof(NoiseFieldParams, element_offset) == 32);
static_assert(sizeof(CarFieldGpu) == 48 + 8 * CARBTF_CAR_MAX_NEIGHBOURS, "CarFieldGpu must match std430");
static_assert(offsetof(CarFieldGpu, tap) == 48 &&
              offsetof(CarFieldGpu, gamma) == 48 + 4 * CARBTF_CAR_MAX_NEIGHBOURS);
static_assert(sizeof(CollapseItemGpu) == 48, "CollapseItemGpu must match std430");
static_assert(sizeof(ColourItemGpu) == 32 + 16 * CARBTF_SYNTH_MAX_CHANNELS +
                                           4 * CARBTF_SYNTH_MAX_CHANNELS * CARBTF_SYNTH_MAX_CHANNELS);
static_assert(sizeof(SynthPassParams) == 36 && sizeof(InterpolateParams) == 112);
static_assert(sizeof(DirectionLookupGpu) == 32 && sizeof(MaterialTablesHeader) == 144);
static_assert(offsetof(MaterialTablesHeader, pair_table) == 64 &&
              offsetof(MaterialTablesHeader, parallax_scale) == 80);
static_assert(offsetof(MaterialTablesHeader, mip_levels) == 108 &&
              offsetof(MaterialTablesHeader, parallax_steps) == 120 &&
              offsetof(MaterialTablesHeader, relief_levels) == 124 &&
              offsetof(MaterialTablesHeader, relief_chroma_levels) == 132);
static_assert(sizeof(RenderFrameUniforms) == 160 + 32 * CARBTF_RENDER_MAX_LIGHTS,
              "RenderFrameUniforms must match std140");
static_assert(offsetof(RenderFrameUniforms, camera) == 128 &&
              offsetof(RenderFrameUniforms, light_position) == 144);
static_assert(offsetof(RenderFrameUniforms, counts) == 144 + 32 * CARBTF_RENDER_MAX_LIGHTS);
}  // namespace carbtf::gpu
#endif

#endif  // CARBTF_GPU_SHARED_H
