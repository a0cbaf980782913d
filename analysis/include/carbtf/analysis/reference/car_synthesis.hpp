// CPU reference of one CAR band's synthesis (DESIGN.md 4.4), the twin the GPU is checked against.
//
// The block [row0, row0 + height) x [col0, col0 + width) of the band's infinite field is computed on the
// region extended by `margin` rows above and `margin` columns on each side (burn-in), with zero values
// outside that region, in row-major order:
//   y(r, c) = ((0 + gamma[0] * y(r + dr0, c + dc0)) + gamma[1] * ...) + sigma * e(r, c)
// in the stored neighbour order, e(r, c) = gaussian_noise(seed, field_id, r, c) in absolute
// coordinates; the block is returned as mean + y. Float32 runs every operation in float with no
// contraction (this library is compiled with -ffp-contract=off); float64 runs the same sequence in
// double on the same noise, as the accuracy reference.
#pragma once

#include <cstdint>
#include <span>

#include "carbtf/engine/material.hpp"
#include "carbtf/engine/noise_block.hpp"

namespace carbtf::reference {

struct CarFieldBlock : NoiseBlock {
  std::uint32_t margin = 32;
};

void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<float> out);
void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<double> out);

}  // namespace carbtf::reference
