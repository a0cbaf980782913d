#version 450
// One level of the pyramid collapse, in place: G = (mean + y) + expand(G_coarse), or mean + y for the
// coarsest level. The expand is the reference's separable one (rows first, then columns, taps
// k = -2..2 in order, weights 2 w_k). Fine pixels go in 2 x 2 blocks on even absolute coordinates: the
// four read the same 3 x 3 coarse pixels, and each horizontal sum is formed once for the block's two
// rows. Items [begin, item_count) of the table (one level's bands) run in one dispatch, one item per z.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"
#include "carbtf_steps.h"

layout(local_size_x = CARBTF_SYNTH_GROUP_X, local_size_y = CARBTF_SYNTH_GROUP_Y, local_size_z = 1) in;

layout(push_constant, std430) uniform Push { SynthPassParams params; };
layout(std430, set = 0, binding = 0) readonly buffer Items { CollapseItemGpu items[]; };
layout(std430, set = 0, binding = 1) buffer Arena { float arena[]; };

// Fine index 2h reads coarse h + 1, h, h - 1 with weights 2 w = 1/8, 3/4, 1/8; fine index 2h + 1 reads
// h + 1, h with 1/2, 1/2, then h again with weight 0: the reference's order (k = -2..2 over the k with
// i - k even), zero tap included, so that the sums are the same bits (adding 0 x can turn a -0 to +0).
float expand_even(float next, float here, float previous) {
  precise float sum = 0.0;
  sum = carbtf_weighted_add(sum, 0.125, next);
  sum = carbtf_weighted_add(sum, 0.75, here);
  sum = carbtf_weighted_add(sum, 0.125, previous);
  return sum;
}
float expand_odd(float next, float here) {
  precise float sum = 0.0;
  sum = carbtf_weighted_add(sum, 0.5, next);
  sum = carbtf_weighted_add(sum, 0.5, here);
  sum = carbtf_weighted_add(sum, 0.0, here);
  return sum;
}

// Coarse value at (row h + dr, column hc + dc) of block column hc, or 0 where the block's fine pixels
// never read it (the h - 1 row or column when the even fine row or column lies outside the window,
// which may be beyond the coarse window).
#define CARBTF_COARSE(dr, dc, needed) \
  ((needed) ? arena[coarse_offset + uint(coarse_r + dr) * pitch + uint(coarse_c + dc)] : 0.0)

// Adds `mean` and, when the level expands, `add` to the fine pixel at `index`, in the reference's order.
#define CARBTF_COLLAPSE_PIXEL(index, add)    \
  {                                          \
    precise float band = mean + arena[index]; \
    if (expands) band = band + add;          \
    arena[index] = band;                     \
  }

void main() {
  uint i = params.begin + gl_WorkGroupID.z;
  if (i >= params.item_count) return;
  int row0 = int(items[i].row0);
  int col0 = int(items[i].col0);
  int rows = int(items[i].rows);
  int cols = int(items[i].cols);
  // Block (hr, hc) covers absolute fine rows 2 hr, 2 hr + 1 and columns 2 hc, 2 hc + 1. An invocation
  // runs CARBTF_COLLAPSE_SPAN blocks of one block row left to right: each block's three coarse columns
  // are its left neighbour's last two and one new, so a block loads 3 coarse pixels, not 9, and the
  // item's fields are read once per span (lavapipe pays per table read).
  int hr = (row0 >> 1) + int(gl_GlobalInvocationID.y);
  int hc0 = (col0 >> 1) + int(gl_GlobalInvocationID.x) * int(CARBTF_COLLAPSE_SPAN);
  int y_even = 2 * hr - row0;  // window coordinate; the odd row is + 1
  if (y_even >= rows || 2 * hc0 - col0 >= cols) return;
  bool row_even_in = y_even >= 0, row_odd_in = y_even + 1 < rows;
  uint fine_offset = items[i].fine_offset;
  uint fine_pitch = items[i].fine_pitch;
  float mean = items[i].mean;
  uint coarse_offset = items[i].coarse_offset;
  bool expands = coarse_offset != CARBTF_NO_FRAME;
  uint pitch = items[i].coarse_pitch;
  int coarse_r = hr - int(items[i].coarse_row0);
  int coarse_c = hc0 - int(items[i].coarse_col0);
  // Coarse rows h + 1 (n), h (h), h - 1 (p) at columns hc - 1 (m), hc (0), hc + 1 (1). Column hc - 1 is
  // needed only by an even fine column inside the window; only the span's first block can lack one.
  bool first_even_in = 2 * hc0 - col0 >= 0;
  float nm = 0.0, n0 = 0.0, n1 = 0.0, hm = 0.0, h0 = 0.0, h1 = 0.0, pm = 0.0, p0 = 0.0, p1 = 0.0;
  if (expands) {
    nm = CARBTF_COARSE(1, -1, first_even_in);
    hm = CARBTF_COARSE(0, -1, first_even_in);
    pm = CARBTF_COARSE(-1, -1, row_even_in && first_even_in);
    n0 = CARBTF_COARSE(1, 0, true);
    h0 = CARBTF_COARSE(0, 0, true);
    p0 = CARBTF_COARSE(-1, 0, row_even_in);
  }
  for (int k = 0; k < int(CARBTF_COLLAPSE_SPAN); ++k, ++coarse_c) {
    int x_even = 2 * (hc0 + k) - col0;  // window coordinate; the odd column is + 1
    if (x_even >= cols) break;
    bool col_even_in = x_even >= 0, col_odd_in = x_even + 1 < cols;
    float add_ee = 0.0, add_eo = 0.0, add_oe = 0.0, add_oo = 0.0;  // [fine row parity][fine column parity]
    if (expands) {
      n1 = CARBTF_COARSE(1, 1, true);
      h1 = CARBTF_COARSE(0, 1, true);
      p1 = CARBTF_COARSE(-1, 1, row_even_in);
      // Horizontal sums of coarse rows h + 1, h, h - 1 for the even and the odd fine column.
      float next_e = expand_even(n1, n0, nm), here_e = expand_even(h1, h0, hm), prev_e = expand_even(p1, p0, pm);
      float next_o = expand_odd(n1, n0), here_o = expand_odd(h1, h0), prev_o = expand_odd(p1, p0);
      add_ee = expand_even(next_e, here_e, prev_e);
      add_eo = expand_even(next_o, here_o, prev_o);
      add_oe = expand_odd(next_e, here_e);
      add_oo = expand_odd(next_o, here_o);
      nm = n0; n0 = n1;
      hm = h0; h0 = h1;
      pm = p0; p0 = p1;
    }
    uint base = fine_offset + uint(y_even) * fine_pitch + uint(x_even);  // modulo 2^32 when y or x is -1
    if (row_even_in && col_even_in) CARBTF_COLLAPSE_PIXEL(base, add_ee)
    if (row_even_in && col_odd_in) CARBTF_COLLAPSE_PIXEL(base + 1u, add_eo)
    if (row_odd_in && col_even_in) CARBTF_COLLAPSE_PIXEL(base + fine_pitch, add_oe)
    if (row_odd_in && col_odd_in) CARBTF_COLLAPSE_PIXEL(base + fine_pitch + 1u, add_oo)
  }
}
