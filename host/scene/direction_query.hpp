// A (light, view) query in degrees against a material: the 9 weights of its measured pairs and the
// subspace images they fall in (`carbtf synth --light --view`).
#pragma once

#include <cstdint>
#include <vector>

#include "carbtf/engine/material/material_directions.hpp"

namespace carbtf::cli {

struct Interpolation {
  PairWeights weights;
  std::vector<std::uint32_t> subspaces;  // those with a non-zero weight
};

// `light` and `view` are (theta, phi) in degrees. CommandError when the material's directions cannot
// be interpolated.
Interpolation interpolation_of(const Material& material, const std::vector<double>& light,
                               const std::vector<double>& view);

// The subspaces to synthesize: `requested` (all of them checked to hold what the query needs), or
// where none are requested, only what the query needs. CommandError naming a missing one.
std::vector<std::uint32_t> subspaces_with(const std::vector<std::uint32_t>& requested,
                                          const Interpolation& interpolation);

}  // namespace carbtf::cli
