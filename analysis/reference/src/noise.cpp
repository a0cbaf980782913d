#include "carbtf/reference/noise.hpp"

#include <algorithm>
#include <cassert>
#include <vector>

#include <carbtf_noise.h>

#include "carbtf/reference/parallel_for.hpp"

namespace carbtf::reference {

using namespace carbtf::gpu;

// Thin wrappers: the arithmetic is written once, for GLSL and C++, in carbtf_noise.h.
std::array<std::uint32_t, 4> philox4x32_10(std::array<std::uint32_t, 4> c, std::array<std::uint32_t, 2> key) {
  carbtf_philox4x32_10(c[0], c[1], c[2], c[3], key[0], key[1]);
  return c;
}

float noise_log(float u) {
  return carbtf_log(u);
}
float noise_cos2pi(float t) {
  return carbtf_cos2pi(t);
}
float noise_sqrt(float v) {
  return carbtf_sqrt(v);
}

float gaussian_noise(std::uint64_t seed, std::uint32_t field_id, std::int32_t row, std::int32_t col) {
  return carbtf_gaussian(static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32), field_id,
                         static_cast<std::uint32_t>(row), static_cast<std::uint32_t>(col));
}

NoiseRowCursor::NoiseRowCursor(std::uint64_t seed, std::uint32_t field_id, std::int32_t row,
                               std::int32_t col0)
    : seed_lo_(static_cast<std::uint32_t>(seed)),
      seed_hi_(static_cast<std::uint32_t>(seed >> 32)),
      field_id_(field_id),
      row_(static_cast<std::uint32_t>(row)),
      col_(static_cast<std::uint32_t>(col0)) {
  carbtf_gaussian4(seed_lo_, seed_hi_, field_id_, row_, col_ >> 2, quad_[0], quad_[1], quad_[2], quad_[3]);
}

float NoiseRowCursor::next() {
  const float value = quad_[col_ & 3u];
  ++col_;
  if ((col_ & 3u) == 0u)
    carbtf_gaussian4(seed_lo_, seed_hi_, field_id_, row_, col_ >> 2, quad_[0], quad_[1], quad_[2], quad_[3]);
  return value;
}

void fill_noise_block(std::uint64_t seed, std::uint32_t field_id, std::int32_t row0, std::int32_t col0,
                      std::uint32_t width, std::uint32_t height, std::span<float> out, unsigned threads) {
  assert(out.size() >= std::size_t{width} * height);
  // Rows wrap modulo 2^32 exactly as on the GPU (uint arithmetic there).
  detail::parallel_for(height, threads, [&](std::size_t r) {
    const auto row =
        static_cast<std::int32_t>(static_cast<std::uint32_t>(row0) + static_cast<std::uint32_t>(r));
    float* line = out.data() + r * width;
    NoiseRowCursor noise(seed, field_id, row, col0);
    for (std::uint32_t c = 0; c < width; ++c) line[c] = noise.next();
  });
}

}  // namespace carbtf::reference
