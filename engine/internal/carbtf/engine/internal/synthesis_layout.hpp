// Where each field of a subspace-image synthesis lies, shared by the GPU synthesizer and the CPU
// reference so that both compute the same regions (docs/design.md 4.4). Internal to carbtf: not
// installed; the engine, carbtf::reference and the tests use it through carbtf_engine_internal.
//
// A block of the unbounded texture is the level-0 region. Level l + 1 covers the coarse support that
// expanding it to level l needs: fine rows [a, b) read coarse rows [floor((a - 1) / 2),
// floor((b + 1) / 2) + 1), and the same for columns. Band (level l, channel c) of subspace s is the CAR
// field with id s * 128 + l * 16 + c; its recursion runs over the level region extended by a burn-in
// margin above and on both sides.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/synthesis/synthesis_block.hpp"

namespace carbtf {

// The value the collapsed band stack of `channel` has on average (the sum of its bands' means, coarsest
// first): the centre the periodic fold blends around, so that it keeps the mean and the variance.
float collapsed_band_mean(const SubspaceModel& model, std::uint32_t channel);

constexpr std::uint32_t field_id_of(std::uint32_t subspace, std::uint32_t level, std::uint32_t channel) {
  return subspace * 128u + level * 16u + channel;
}

// floor(a / 2) for any sign.
constexpr std::int64_t floor_half(std::int64_t a) {
  return a >= 0 ? a / 2 : -((-a + 1) / 2);
}

TextureRegion coarse_support(const TextureRegion& fine);

// The regions of levels 0 .. levels - 1 for an output block.
std::vector<TextureRegion> level_regions(const TextureRegion& block, std::uint32_t levels);

// Rows above and columns to each side that a neighbourhood reaches, at least 1: the frame a field is
// stored with.
std::uint32_t car_frame_pad(std::span<const CarNeighbour> neighbourhood);

// The burn-in a band's recursion needs, capped at `limit` (the request's margin): the fewest rows and
// columns m with rho^m <= kBurnInResidual, rho the largest characteristic root modulus of the recursion
// (car_stability.hpp). Started from zeros m rows and columns before the level region, the recursion's
// start then leaves less than that share of a standard deviation in the region (docs/design.md 4.4).
// 0 for a band without neighbours. The GPU plan and the CPU reference both take each band's margin from
// here, so that their regions, and block-wise frames, agree.
inline constexpr double kBurnInResidual = 1e-3;
std::uint32_t band_burn_in(const CarBandModel& band, std::uint32_t limit);

// The region a band's recursion runs over: its level region extended by the burn-in margin above and on
// both sides.
TextureRegion car_region(const TextureRegion& level_region, std::uint32_t margin);

// The wavefront skew a: pixel (r, c) can run at step a * r + c, a = max over neighbours with dr < 0 of
// ceil((dc + 1) / -dr), at least 1. Every neighbour of a pixel then runs at an earlier step.
std::uint32_t car_wavefront_skew(std::span<const CarNeighbour> neighbourhood);

}  // namespace carbtf
