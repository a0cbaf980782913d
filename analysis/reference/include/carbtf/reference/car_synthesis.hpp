// CPU reference of one CAR band's synthesis (docs/design.md 4.4), the twin the GPU is checked against.
//
// The block [row0, row0 + height) x [col0, col0 + width) of the band's infinite field is computed on the
// region extended by `margin` rows above and `margin` columns on each side (burn-in, car_region()), with
// values outside that region taken from `frame` (block initialization values, laid out as
// synthesis_block.hpp's car_frame_floats() describes) or zero, in row-major order:
//   y(r, c) = ((0 + gamma[0] * y(r + dr0, c + dc0)) + gamma[1] * ...) + sigma * e(r, c)
// in the stored neighbour order, e(r, c) = gaussian_noise(seed, field_id, r, c) in absolute
// coordinates; the block is returned as mean + y. Float32 runs every operation in float with no
// contraction (this library is compiled with -ffp-contract=off); float64 runs the same sequence in
// double on the same noise, as the accuracy reference.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/internal/synthesis_layout.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/synthesis/noise_block.hpp"

namespace carbtf::reference {

struct CarFieldBlock : NoiseBlock {
  std::uint32_t margin = 32;
  // Empty: a zero frame. Otherwise car_frame_floats(car region, car_frame_pad(neighbourhood)) values.
  std::span<const float> frame;
};

// Throws std::invalid_argument for an output span or a frame of the wrong size.
void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<float> out);
void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<double> out);

// The whole recursion y (mean not added) of the block's CAR region with its frame, row-major over
// car_region() grown by the frame pad above and on both sides: what a larger synthesis gives a block's
// frames (extract_car_frame()). Float32, as synthesize_car_block() computes it.
struct CarFieldValues {
  TextureRegion region;  // absolute coordinates of values[0] and the extent
  std::vector<float> values;
};
CarFieldValues synthesize_car_field(const CarBandModel& band, const CarFieldBlock& block);

}  // namespace carbtf::reference
