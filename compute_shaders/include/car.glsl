// One pixel of a CAR recursion, shared by car_serial.comp and car_wavefront.comp: region pixel (r, c)
// becomes y = sum_k gamma[k] y(neighbour k) + sigma e, summed from 0 in neighbour order with no fused
// multiply-add, as the CPU reference does (analysis/reference/src/car_synthesis.cpp). The caller brings
// the noise e: the serial scheme draws four at a time, the wavefront scheme reads what car_prepare wrote
// in the pixel's place (its invocations move between rows, so none could keep a row's four). The taps
// are unrolled because lavapipe caps loop iterations per invocation (docs/design.md 6), and the frame
// makes every neighbour read in bounds. Needs `arena`.
#ifndef CARBTF_CAR_GLSL
#define CARBTF_CAR_GLSL

#include "carbtf_steps.h"

// The taps a kernel unrolls, a multiple of 4 up to CARBTF_CAR_MAX_NEIGHBOURS: the build compiles
// car_serial and car_wavefront once per count (compute_shaders/CMakeLists.txt) and the engine runs the
// smallest that covers each run of fields (docs/design.md 4.4), because lavapipe executes an unrolled
// tap's masked loads whether or not a lane needs them. The count is a preprocessor macro, so each
// variant is a plain shader module.
#ifndef CARBTF_CAR_TAPS
#define CARBTF_CAR_TAPS 16
#endif

#define CARBTF_CAR_TAP(k)                                                         \
  if (k < field.neighbour_count) {                                                \
    acc = carbtf_weighted_add(acc, field.gamma[k], arena[uint(int(base) + field.tap[k])]); \
  }

void carbtf_car_pixel(in CarFieldGpu field, uint base, float e) {
  precise float acc = 0.0;
  CARBTF_CAR_TAP(0u) CARBTF_CAR_TAP(1u) CARBTF_CAR_TAP(2u) CARBTF_CAR_TAP(3u)
#if CARBTF_CAR_TAPS > 4
  CARBTF_CAR_TAP(4u) CARBTF_CAR_TAP(5u) CARBTF_CAR_TAP(6u) CARBTF_CAR_TAP(7u)
#endif
#if CARBTF_CAR_TAPS > 8
  CARBTF_CAR_TAP(8u) CARBTF_CAR_TAP(9u) CARBTF_CAR_TAP(10u) CARBTF_CAR_TAP(11u)
#endif
#if CARBTF_CAR_TAPS > 12
  CARBTF_CAR_TAP(12u) CARBTF_CAR_TAP(13u) CARBTF_CAR_TAP(14u) CARBTF_CAR_TAP(15u)
#endif
  precise float value = carbtf_car_value(acc, field.sigma, e);
  arena[base] = value;
}

#endif  // CARBTF_CAR_GLSL
