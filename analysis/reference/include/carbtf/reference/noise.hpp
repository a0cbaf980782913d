// CPU reference of the counter-based Gaussian noise (docs/design.md 4.4; spec in
// compute_shaders/include/carbtf_gpu_shared.h). Float32 results equal the GPU's bit for bit: the
// arithmetic is the same sequence of correctly rounded +, -, * (this library is compiled with
// -ffp-contract=off). All functions are pure and thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace carbtf::reference {

// Philox4x32-10 (Salmon et al. 2011) of `counter` under `key`.
std::array<std::uint32_t, 4> philox4x32_10(std::array<std::uint32_t, 4> counter,
                                           std::array<std::uint32_t, 2> key);

// The division-free building blocks, exposed so tests can measure their accuracy.
float noise_log(float u);     // ln(u), u in [2^-24, 1]
float noise_cos2pi(float t);  // cos(2 pi t), t in [0, 1)
float noise_sqrt(float v);    // sqrt(v), v >= 0

// N(0,1) sample at (seed, field, row, col); row and col are taken modulo 2^32 (negative rows are fine).
float gaussian_noise(std::uint64_t seed, std::uint32_t field_id, std::int32_t row, std::int32_t col);

// The samples of one row of a field, left to right, at one Philox call per four columns (the calls the
// GPU's serial CAR makes): next() returns the sample at col0, col0 + 1, ...
class NoiseRowCursor {
 public:
  NoiseRowCursor(std::uint64_t seed, std::uint32_t field_id, std::int32_t row, std::int32_t col0);
  float next();

 private:
  std::uint32_t seed_lo_, seed_hi_, field_id_, row_, col_;
  float quad_[4] = {};
};

// Fills `out` (width * height floats, row-major) with the block whose top-left sample is (row0, col0),
// on `threads` threads (0: all hardware threads).
void fill_noise_block(std::uint64_t seed, std::uint32_t field_id, std::int32_t row0, std::int32_t col0,
                      std::uint32_t width, std::uint32_t height, std::span<float> out, unsigned threads = 0);

}  // namespace carbtf::reference
