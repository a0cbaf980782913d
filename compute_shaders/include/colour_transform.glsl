#ifndef CARBTF_COLOUR_TRANSFORM_GLSL
#define CARBTF_COLOUR_TRANSFORM_GLSL
// The colour pass (colour_transform.comp, and colour_fold.comp with CARBTF_COLOUR_FOLD).
// Inverse colour transform into the output layer: rgb_i = mean_i + sum_j T[i][j] G_j, summed in channel
// order from the mean. A batch may hold only some channels of an image; the next batch continues the
// sums from the stored layer, which is exact because the partial sums are float32 on both sides. A
// periodic item folds each channel's G_0 first (carbtf_periodic.h): its fold texels are written by
// colour_fold.comp.
#include "carbtf_gpu_shared.h"
#include "carbtf_periodic.h"
#include "carbtf_steps.h"

#ifndef CARBTF_COLOUR_FOLD
layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;
#else
layout(local_size_x = CARBTF_FOLD_GROUP, local_size_y = 1, local_size_z = 1) in;
#endif

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Items { ColourItemGpu items[]; };
layout(std430, set = 0, binding = 1) readonly buffer Arena { float arena[]; };
layout(set = 0, binding = 2, rgba32f) uniform image2DArray images;

// Adds T[c][j] * g to channel c's sum for every output channel, g = band(j), constant indices only
// (dynamic indexing of a vector makes lavapipe spill it to memory).
#define CARBTF_COLOUR_TERM(j, band)                                                                 \
  if (j >= begin && j < end) {                                                                      \
    float g = band(j);                                                                              \
    acc.x = carbtf_weighted_add(acc.x, t[0u * channels + j], g);                                   \
    if (channels > 1u) acc.y = carbtf_weighted_add(acc.y, t[1u * channels + j], g);                \
    if (channels > 2u) acc.z = carbtf_weighted_add(acc.z, t[2u * channels + j], g);                \
    if (channels > 3u) acc.w = carbtf_weighted_add(acc.w, t[3u * channels + j], g);                \
  }
#define CARBTF_BAND_AT(j, col, row) arena[offset[j] + (row) * pitch[j] + (col)]
#define CARBTF_PLAIN_BAND(j) CARBTF_BAND_AT(j, x, y)
#define CARBTF_FOLDED_BAND(j)                                                                       \
  carbtf_fold(items[i].fold_centre[j], CARBTF_BAND_AT(j, x, y), CARBTF_BAND_AT(j, fold_x, y),          \
              CARBTF_BAND_AT(j, x, fold_y), CARBTF_BAND_AT(j, fold_x, fold_y), kx, tx, ky, ty)
// One output texel (x, y) from the bands as `band` reads them.
#define CARBTF_COLOUR_TEXEL(band)                                                                   \
  {                                                                                                 \
    ivec3 texel = ivec3(int(x), int(y), layer);                                                     \
    precise vec4 acc = begin == 0u ? start : imageLoad(images, texel);                              \
    CARBTF_COLOUR_TERM(0u, band)                                                                    \
    CARBTF_COLOUR_TERM(1u, band)                                                                    \
    CARBTF_COLOUR_TERM(2u, band)                                                                    \
    CARBTF_COLOUR_TERM(3u, band)                                                                    \
    imageStore(images, texel, acc);                                                                 \
  }

// The item's fields every texel needs, read once per invocation (lavapipe pays per table read).
#define CARBTF_COLOUR_ITEM                                                                          \
  uint cols = items[i].cols;                                                                        \
  uint channels = items[i].channels;                                                                \
  uint begin = items[i].channel_begin;                                                              \
  uint end = items[i].channel_end;                                                                  \
  int layer = int(items[i].layer);                                                                  \
  uint offset[CARBTF_SYNTH_MAX_CHANNELS] = items[i].offset;                                         \
  uint pitch[CARBTF_SYNTH_MAX_CHANNELS] = items[i].pitch;                                           \
  float t[CARBTF_SYNTH_MAX_CHANNELS * CARBTF_SYNTH_MAX_CHANNELS] = items[i].transform;              \
  vec4 start = vec4(items[i].mean[0], channels > 1u ? items[i].mean[1] : 0.0,                       \
                    channels > 2u ? items[i].mean[2] : 0.0, channels > 3u ? items[i].mean[3] : 1.0);

#ifndef CARBTF_COLOUR_FOLD
// Every texel beyond the fold (all of a plain image), CARBTF_COLOUR_SPAN of a row per invocation.
// lavapipe runs both sides of a branch under masks, so the fold's texels are left to their own pass.
void main() {
  uint i = gl_WorkGroupID.z;
  if (i >= params.item_count) return;
  uint y = gl_GlobalInvocationID.y;
  if (y >= items[i].rows) return;
  CARBTF_COLOUR_ITEM
  uint overlap = items[i].overlap;
  for (uint k = 0u; k < CARBTF_COLOUR_SPAN; ++k) {
    uint x = gl_GlobalInvocationID.x * CARBTF_COLOUR_SPAN + k;
    if (x >= cols) break;
    if (x < overlap || y < overlap) continue;
    CARBTF_COLOUR_TEXEL(CARBTF_PLAIN_BAND)
  }
}
#else
// The fold's texels, one per invocation along x: the first `overlap` columns of every row, then the
// rest of the first `overlap` rows.
void main() {
  uint i = gl_WorkGroupID.z;
  if (i >= params.item_count) return;
  uint rows = items[i].rows;
  uint overlap = items[i].overlap;
  CARBTF_COLOUR_ITEM
  uint index = gl_GlobalInvocationID.x;
  uint left = overlap * rows;
  if (overlap == 0u || index >= left + overlap * (cols - overlap)) return;
  uint x = index < left ? index % overlap : overlap + (index - left) % (cols - overlap);
  uint y = index < left ? index / overlap : (index - left) / (cols - overlap);
  float inv_overlap = items[i].inv_overlap;
  float kx = carbtf_fold_keep(x, overlap, inv_overlap);
  float tx = carbtf_fold_take(x, overlap, inv_overlap);
  float ky = carbtf_fold_keep(y, overlap, inv_overlap);
  float ty = carbtf_fold_take(y, overlap, inv_overlap);
  uint fold_x = x < overlap ? x + cols : x;
  uint fold_y = y < overlap ? y + rows : y;
  CARBTF_COLOUR_TEXEL(CARBTF_FOLDED_BAND)
}
#endif

#endif  // CARBTF_COLOUR_TRANSFORM_GLSL
