// Counter-based Gaussian noise (docs/design.md 4.4), written once for GLSL and C++: the shaders include
// it as "carbtf_noise.h", the CPU reference as <carbtf_noise.h> (functions in carbtf::gpu). Every float
// operation is limited to +, -, * (Vulkan guarantees correct rounding for nothing more) and is
// `precise` in GLSL (no fused multiply-add); the C++ side is compiled with -ffp-contract=off. Float
// literals carry the f suffix so that C++ computes in float as GLSL does. The GPU field then equals the
// CPU float32 reference bit for bit by construction. Spec: carbtf_gpu_shared.h, "Gaussian noise".
#ifndef CARBTF_NOISE_H
#define CARBTF_NOISE_H

#include "carbtf_gpu_shared.h"

#ifdef __cplusplus
#include <bit>
namespace carbtf::gpu {
#define CARBTF_PRECISE
#define CARBTF_INOUT(type) type&
#define CARBTF_OUT(type) type&
// GLSL built-ins the functions below use, for C++.
inline constexpr uint floatBitsToUint(float value) {
  return std::bit_cast<uint>(value);
}
inline constexpr float uintBitsToFloat(uint value) {
  return std::bit_cast<float>(value);
}
inline constexpr void umulExtended(uint a, uint b, uint& high, uint& low) {
  const std::uint64_t product = std::uint64_t{a} * b;
  high = uint(product >> 32);
  low = uint(product);
}
#else
#define CARBTF_PRECISE precise
#define CARBTF_INOUT(type) inout type
#define CARBTF_OUT(type) out type
#endif

// Philox4x32-10 of counter (c0, c1, c2, c3) under key (k0, k1), in place.
CARBTF_FUNCTION void carbtf_philox4x32_10(CARBTF_INOUT(uint) c0, CARBTF_INOUT(uint) c1, CARBTF_INOUT(uint) c2,
                                          CARBTF_INOUT(uint) c3, uint k0, uint k1) {
  for (uint round = 0u; round < CARBTF_PHILOX_ROUNDS; ++round) {
    if (round > 0u) {
      k0 += CARBTF_PHILOX_W0;
      k1 += CARBTF_PHILOX_W1;
    }
    uint hi0 = 0u, lo0 = 0u, hi1 = 0u, lo1 = 0u;
    umulExtended(CARBTF_PHILOX_M0, c0, hi0, lo0);
    umulExtended(CARBTF_PHILOX_M1, c2, hi1, lo1);
    uint next0 = hi1 ^ c1 ^ k0;
    uint next2 = hi0 ^ c3 ^ k1;
    c0 = next0;
    c1 = lo1;
    c2 = next2;
    c3 = lo0;
  }
}

// ln(u) for u in [2^-24, 1].
CARBTF_FUNCTION float carbtf_log(float u) {
  uint bits = floatBitsToUint(u);
  CARBTF_PRECISE float exponent = float(int(bits >> 23u) - 127);
  CARBTF_PRECISE float mantissa = uintBitsToFloat((bits & 0x007FFFFFu) | 0x3F800000u);
  if (mantissa > CARBTF_SQRT2) {
    mantissa = mantissa * 0.5f;
    exponent = exponent + 1.0f;
  }
  CARBTF_PRECISE float x = mantissa - 1.0f;
  CARBTF_PRECISE float p = CARBTF_LOG1P_C13;
  p = p * x + CARBTF_LOG1P_C12;
  p = p * x + CARBTF_LOG1P_C11;
  p = p * x + CARBTF_LOG1P_C10;
  p = p * x + CARBTF_LOG1P_C9;
  p = p * x + CARBTF_LOG1P_C8;
  p = p * x + CARBTF_LOG1P_C7;
  p = p * x + CARBTF_LOG1P_C6;
  p = p * x + CARBTF_LOG1P_C5;
  p = p * x + CARBTF_LOG1P_C4;
  p = p * x + CARBTF_LOG1P_C3;
  p = p * x + CARBTF_LOG1P_C2;
  p = p * x + CARBTF_LOG1P_C1;
  CARBTF_PRECISE float result = exponent * CARBTF_LN2 + x * p;
  return result;
}

// cos(2 pi t) for t in [0, 1).
CARBTF_FUNCTION float carbtf_cos2pi(float t) {
  CARBTF_PRECISE float r = t;
  if (r >= 0.5f) r = 1.0f - r;  // exact (Sterbenz)
  CARBTF_PRECISE float sign = 1.0f;
  if (r > 0.25f) {
    r = 0.5f - r;  // exact (Sterbenz)
    sign = -1.0f;
  }
  CARBTF_PRECISE float z = r * r;
  CARBTF_PRECISE float p = CARBTF_COS2PI_C7;
  p = p * z + CARBTF_COS2PI_C6;
  p = p * z + CARBTF_COS2PI_C5;
  p = p * z + CARBTF_COS2PI_C4;
  p = p * z + CARBTF_COS2PI_C3;
  p = p * z + CARBTF_COS2PI_C2;
  p = p * z + CARBTF_COS2PI_C1;
  p = p * z + CARBTF_COS2PI_C0;
  CARBTF_PRECISE float result = sign * p;
  return result;
}

// sqrt(v) for v >= 0: three Newton steps on 1/sqrt(v) from the integer seed, then v * (1/sqrt(v)).
CARBTF_FUNCTION float carbtf_sqrt(float v) {
  if (v == 0.0f) return 0.0f;
  CARBTF_PRECISE float y = uintBitsToFloat(CARBTF_RSQRT_MAGIC - (floatBitsToUint(v) >> 1u));
  CARBTF_PRECISE float half_v = 0.5f * v;
  y = y * (1.5f - half_v * y * y);
  y = y * (1.5f - half_v * y * y);
  y = y * (1.5f - half_v * y * y);
  CARBTF_PRECISE float result = v * y;
  return result;
}

// sqrt(-2 ln u) cos(2 pi v) and sqrt(-2 ln u) sin(2 pi v) of the words' top 24 bits:
// u = ((u_word >> 8) + 1) 2^-24 in [2^-24, 1], v = (v_word >> 8) 2^-24 in [0, 1).
CARBTF_FUNCTION void carbtf_box_muller(uint u_word, uint v_word, CARBTF_OUT(float) cos_sample,
                                       CARBTF_OUT(float) sin_sample) {
  CARBTF_PRECISE float u = float((u_word >> 8u) + 1u) * CARBTF_TWO_POW_MINUS_24;
  uint v = v_word >> 8u;
  CARBTF_PRECISE float radius = carbtf_sqrt(-2.0f * carbtf_log(u));
  CARBTF_PRECISE float c = radius * carbtf_cos2pi(float(v) * CARBTF_TWO_POW_MINUS_24);
  CARBTF_PRECISE float s =
      radius * carbtf_cos2pi(float((v + 0xC00000u) & 0xFFFFFFu) * CARBTF_TWO_POW_MINUS_24);
  cos_sample = c;
  sin_sample = s;
}

// The four N(0,1) samples of columns 4 quad .. 4 quad + 3 of (seed, field id, row), from one Philox call.
CARBTF_FUNCTION void carbtf_gaussian4(uint seed_lo, uint seed_hi, uint field_id, uint row, uint quad,
                                      CARBTF_OUT(float) g0, CARBTF_OUT(float) g1, CARBTF_OUT(float) g2,
                                      CARBTF_OUT(float) g3) {
  uint c0 = quad, c1 = row, c2 = field_id, c3 = 0u;
  carbtf_philox4x32_10(c0, c1, c2, c3, seed_lo, seed_hi);
  carbtf_box_muller(c0, c1, g0, g1);
  carbtf_box_muller(c2, c3, g2, g3);
}

// Sample `index` (0 .. 3) of four; a switch rather than an array, which GLSL and C++ write differently.
CARBTF_FUNCTION float carbtf_pick4(float g0, float g1, float g2, float g3, uint index) {
  return index == 0u ? g0 : index == 1u ? g1 : index == 2u ? g2 : g3;
}

// N(0,1) at (seed, field id, row, col); rows and columns are taken modulo 2^32. One Philox call for one
// sample: loops over a row use carbtf_gaussian4 and all four.
CARBTF_FUNCTION float carbtf_gaussian(uint seed_lo, uint seed_hi, uint field_id, uint row, uint col) {
  float g0 = 0.0f, g1 = 0.0f, g2 = 0.0f, g3 = 0.0f;
  carbtf_gaussian4(seed_lo, seed_hi, field_id, row, col >> 2u, g0, g1, g2, g3);
  return carbtf_pick4(g0, g1, g2, g3, col & 3u);
}

#ifdef __cplusplus
}  // namespace carbtf::gpu
#endif

#endif  // CARBTF_NOISE_H
