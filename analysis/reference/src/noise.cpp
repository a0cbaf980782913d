#include "carbtf/reference/noise.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <vector>

#include <carbtf_gpu_shared.h>

#include "carbtf/reference/parallel_for.hpp"

namespace carbtf::reference {

using namespace carbtf::gpu;

std::array<std::uint32_t, 4> philox4x32_10(std::array<std::uint32_t, 4> c, std::array<std::uint32_t, 2> key) {
  for (std::uint32_t round = 0; round < CARBTF_PHILOX_ROUNDS; ++round) {
    if (round > 0) {
      key[0] += CARBTF_PHILOX_W0;
      key[1] += CARBTF_PHILOX_W1;
    }
    const std::uint64_t product0 = std::uint64_t{CARBTF_PHILOX_M0} * c[0];
    const std::uint64_t product1 = std::uint64_t{CARBTF_PHILOX_M1} * c[2];
    const auto hi0 = static_cast<std::uint32_t>(product0 >> 32), lo0 = static_cast<std::uint32_t>(product0);
    const auto hi1 = static_cast<std::uint32_t>(product1 >> 32), lo1 = static_cast<std::uint32_t>(product1);
    c = {hi1 ^ c[1] ^ key[0], lo1, hi0 ^ c[3] ^ key[1], lo0};
  }
  return c;
}

// The three functions below mirror compute_shaders/include/noise.glsl statement for statement.
float noise_log(float u) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(u);
  float exponent = static_cast<float>(static_cast<std::int32_t>(bits >> 23) - 127);
  float mantissa = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u);
  if (mantissa > CARBTF_SQRT2) {
    mantissa = mantissa * 0.5f;
    exponent = exponent + 1.0f;
  }
  const float x = mantissa - 1.0f;
  float p = CARBTF_LOG1P_C13;
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
  return exponent * CARBTF_LN2 + x * p;
}

float noise_cos2pi(float t) {
  float r = t;
  if (r >= 0.5f) r = 1.0f - r;
  float sign = 1.0f;
  if (r > 0.25f) {
    r = 0.5f - r;
    sign = -1.0f;
  }
  const float z = r * r;
  float p = CARBTF_COS2PI_C7;
  p = p * z + CARBTF_COS2PI_C6;
  p = p * z + CARBTF_COS2PI_C5;
  p = p * z + CARBTF_COS2PI_C4;
  p = p * z + CARBTF_COS2PI_C3;
  p = p * z + CARBTF_COS2PI_C2;
  p = p * z + CARBTF_COS2PI_C1;
  p = p * z + CARBTF_COS2PI_C0;
  return sign * p;
}

float noise_sqrt(float v) {
  if (v == 0.0f) return 0.0f;
  float y = std::bit_cast<float>(CARBTF_RSQRT_MAGIC - (std::bit_cast<std::uint32_t>(v) >> 1));
  const float half_v = 0.5f * v;
  y = y * (1.5f - half_v * y * y);
  y = y * (1.5f - half_v * y * y);
  y = y * (1.5f - half_v * y * y);
  return v * y;
}

float gaussian_noise(std::uint64_t seed, std::uint32_t field_id, std::int32_t row, std::int32_t col) {
  const auto words = philox4x32_10(
      {static_cast<std::uint32_t>(col), static_cast<std::uint32_t>(row), field_id, 0u},
      {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)});
  const float u1 = static_cast<float>((words[0] >> 8) + 1u) * CARBTF_TWO_POW_MINUS_24;
  const float u2 = static_cast<float>(words[1] >> 8) * CARBTF_TWO_POW_MINUS_24;
  const float radius = noise_sqrt(-2.0f * noise_log(u1));
  return radius * noise_cos2pi(u2);
}

void fill_noise_block(std::uint64_t seed, std::uint32_t field_id, std::int32_t row0, std::int32_t col0,
                      std::uint32_t width, std::uint32_t height, std::span<float> out, unsigned threads) {
  assert(out.size() >= std::size_t{width} * height);
  // Rows wrap modulo 2^32 exactly as on the GPU (uint arithmetic there).
  detail::parallel_for(height, threads, [&](std::size_t r) {
    const auto row = static_cast<std::int32_t>(static_cast<std::uint32_t>(row0) + static_cast<std::uint32_t>(r));
    float* line = out.data() + r * width;
    for (std::uint32_t c = 0; c < width; ++c) {
      line[c] = gaussian_noise(seed, field_id, row, static_cast<std::int32_t>(static_cast<std::uint32_t>(col0) + c));
    }
  });
}

}  // namespace carbtf::reference
