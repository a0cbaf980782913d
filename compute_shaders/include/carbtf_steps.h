// The arithmetic of one synthesis step, written once for GLSL and C++ (docs/design.md 4.4): the CAR
// recursion's taps and noise term, the collapse's weighted expand taps and the inverse colour
// transform's terms. Both languages call these, so the order of operations is the same by construction;
// `precise` in GLSL and -ffp-contract=off in C++ keep every product and sum rounded on its own. In C++
// each is a template over the float type, so the float64 accuracy reference runs the same steps.
#ifndef CARBTF_STEPS_H
#define CARBTF_STEPS_H

#include "carbtf_noise.h"

#ifdef __cplusplus
namespace carbtf::gpu {
#define CARBTF_STEP        \
  template <typename real> \
  inline constexpr
#else
#define CARBTF_STEP
#define real float
#endif

// A weighted term added to a running sum: one CAR tap (gamma times a neighbour), one expand tap (a
// filter weight times a coarse value) or one colour term (a transform entry times a band).
CARBTF_STEP real carbtf_weighted_add(real sum, real weight, real value) {
  CARBTF_PRECISE real result = sum + weight * value;
  return result;
}

// A CAR pixel from its taps' sum and its noise sample: y = sum + sigma e.
CARBTF_STEP real carbtf_car_value(real taps, real sigma, real noise) {
  CARBTF_PRECISE real result = taps + sigma * noise;
  return result;
}

#ifdef __cplusplus
#undef CARBTF_STEP
}  // namespace carbtf::gpu
#else
#undef real
#undef CARBTF_STEP
#endif

#endif  // CARBTF_STEPS_H
