// The periodic fold of a synthesis (docs/design.md 4.4, "Periodic output"), written once for GLSL and
// C++ like the noise it takes its cosine from: + - * only, `precise` in GLSL, so the GPU's periodic
// images equal the CPU reference's bit for bit.
#ifndef CARBTF_PERIODIC_H
#define CARBTF_PERIODIC_H

#include "carbtf_noise.h"

#ifdef __cplusplus
namespace carbtf::gpu {
#endif

// The weight output index i keeps of the field at i (sin(pi u / 2), u = (i + 1/2) / overlap), and the
// weight it takes from the field one period further (cos(pi u / 2)); 1 and 0 from index `overlap` on.
// inv_overlap is 1 / overlap as the host rounds it, so both languages start from the same float.
CARBTF_FUNCTION float carbtf_fold_keep(uint i, uint overlap, float inv_overlap) {
  if (i >= overlap) return 1.0f;
  CARBTF_PRECISE float u = (float(i) + 0.5f) * inv_overlap;
  CARBTF_PRECISE float t = (1.0f - u) * 0.25f;
  return carbtf_cos2pi(t);
}
CARBTF_FUNCTION float carbtf_fold_take(uint i, uint overlap, float inv_overlap) {
  if (i >= overlap) return 0.0f;
  CARBTF_PRECISE float u = (float(i) + 0.5f) * inv_overlap;
  CARBTF_PRECISE float t = u * 0.25f;
  return carbtf_cos2pi(t);
}

// One folded value around `centre`: g00 at (x, y), g10 one period right, g01 one period down, g11
// both; kx, tx the column weights and ky, ty the row weights above. In C++ a template over the float
// type, so the float64 reference folds with the same steps.
#ifdef __cplusplus
template <typename real>
inline constexpr
#else
#define real float
#endif
    real
    carbtf_fold(real centre, real g00, real g10, real g01, real g11, real kx, real tx, real ky, real ty) {
  CARBTF_PRECISE real top = kx * (g00 - centre) + tx * (g10 - centre);
  CARBTF_PRECISE real bottom = kx * (g01 - centre) + tx * (g11 - centre);
  CARBTF_PRECISE real result = centre + (ky * top + ty * bottom);
  return result;
}
#ifndef __cplusplus
#undef real
#endif

#ifdef __cplusplus
// The host side of the fold: `grown` is (width + overlap) x (height + overlap), row-major; output texel
// (x, y) goes to out[(y * width + x) * stride]. The same float operations as colour_fold.comp (the CPU
// reference's images, the range map's fold); Real = double folds with the same steps in double.
template <typename Real, typename Grown>
void carbtf_fold_grid(const Grown& grown, uint width, uint height, uint overlap, Real centre, Real* out,
                      std::size_t stride) {
  const std::size_t pitch = std::size_t{width} + overlap;
  const float inv_overlap = overlap > 0 ? 1.0f / float(overlap) : 0.0f;
  for (uint y = 0; y < height; ++y) {
    const Real ky = carbtf_fold_keep(y, overlap, inv_overlap), ty = carbtf_fold_take(y, overlap, inv_overlap);
    const std::size_t below = (y < overlap ? y + height : y) * pitch, row = y * pitch;
    for (uint x = 0; x < width; ++x) {
      Real value = grown[row + x];
      if (x < overlap || y < overlap) {
        const std::size_t right = x < overlap ? x + width : x;
        value = carbtf_fold<Real>(centre, value, grown[row + right], grown[below + x], grown[below + right],
                                  carbtf_fold_keep(x, overlap, inv_overlap),
                                  carbtf_fold_take(x, overlap, inv_overlap), ky, ty);
      }
      out[(std::size_t{y} * width + x) * stride] = value;
    }
  }
}

}  // namespace carbtf::gpu
#endif

#endif  // CARBTF_PERIODIC_H
