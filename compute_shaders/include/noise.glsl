// Counter-based Gaussian noise, the GLSL twin of analysis/reference/src/noise.cpp. Every float
// operation is `precise` (no fused multiply-add) and limited to +, -, *, so that the result is the
// same bit pattern as the CPU float32 reference. Spec: carbtf_gpu_shared.h, "Gaussian noise".
#ifndef CARBTF_NOISE_GLSL
#define CARBTF_NOISE_GLSL

uvec4 carbtf_philox4x32_10(uvec4 counter, uvec2 key) {
  for (uint round = 0u; round < CARBTF_PHILOX_ROUNDS; ++round) {
    if (round > 0u) key += uvec2(CARBTF_PHILOX_W0, CARBTF_PHILOX_W1);
    uint hi0, lo0, hi1, lo1;
    umulExtended(CARBTF_PHILOX_M0, counter.x, hi0, lo0);
    umulExtended(CARBTF_PHILOX_M1, counter.z, hi1, lo1);
    counter = uvec4(hi1 ^ counter.y ^ key.x, lo1, hi0 ^ counter.w ^ key.y, lo0);
  }
  return counter;
}

// ln(u) for u in [2^-24, 1].
float carbtf_log(float u) {
  uint bits = floatBitsToUint(u);
  precise float exponent = float(int(bits >> 23u) - 127);
  precise float mantissa = uintBitsToFloat((bits & 0x007FFFFFu) | 0x3F800000u);
  if (mantissa > CARBTF_SQRT2) {
    mantissa = mantissa * 0.5;
    exponent = exponent + 1.0;
  }
  precise float x = mantissa - 1.0;
  precise float p = CARBTF_LOG1P_C13;
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
  precise float result = exponent * CARBTF_LN2 + x * p;
  return result;
}

// cos(2 pi t) for t in [0, 1).
float carbtf_cos2pi(float t) {
  precise float r = t;
  if (r >= 0.5) r = 1.0 - r;  // exact (Sterbenz)
  precise float sign = 1.0;
  if (r > 0.25) {
    r = 0.5 - r;  // exact (Sterbenz)
    sign = -1.0;
  }
  precise float z = r * r;
  precise float p = CARBTF_COS2PI_C7;
  p = p * z + CARBTF_COS2PI_C6;
  p = p * z + CARBTF_COS2PI_C5;
  p = p * z + CARBTF_COS2PI_C4;
  p = p * z + CARBTF_COS2PI_C3;
  p = p * z + CARBTF_COS2PI_C2;
  p = p * z + CARBTF_COS2PI_C1;
  p = p * z + CARBTF_COS2PI_C0;
  precise float result = sign * p;
  return result;
}

// sqrt(v) for v >= 0: three Newton steps on 1/sqrt(v) from the integer seed, then v * (1/sqrt(v)).
float carbtf_sqrt(float v) {
  if (v == 0.0) return 0.0;
  precise float y = uintBitsToFloat(CARBTF_RSQRT_MAGIC - (floatBitsToUint(v) >> 1u));
  precise float half_v = 0.5 * v;
  y = y * (1.5 - half_v * y * y);
  y = y * (1.5 - half_v * y * y);
  y = y * (1.5 - half_v * y * y);
  precise float result = v * y;
  return result;
}

float carbtf_gaussian(uvec2 seed, uint field_id, uint row, uint col) {
  uvec4 words = carbtf_philox4x32_10(uvec4(col, row, field_id, 0u), seed);
  precise float u1 = float((words.x >> 8u) + 1u) * CARBTF_TWO_POW_MINUS_24;
  precise float u2 = float(words.y >> 8u) * CARBTF_TWO_POW_MINUS_24;
  precise float radius = carbtf_sqrt(-2.0 * carbtf_log(u1));
  precise float result = radius * carbtf_cos2pi(u2);
  return result;
}

#endif  // CARBTF_NOISE_GLSL
