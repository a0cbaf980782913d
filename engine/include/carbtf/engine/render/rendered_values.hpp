// Material numbers as carbtf's render pass reads them (rounded to the precision its tables hold), for
// CPU twins of its fragment stage. Plain functions, no Vulkan: part of carbtf::model.
#pragma once

#include <array>
#include <cstdint>

#include "carbtf/engine/material/material.hpp"

namespace carbtf {

// A subspace's tone weight (SubspaceModel::tone_weight) as the render pass reads it: rounded to the half
// float the pair table holds (MaterialTablesHeader::pair_table), for CPU twins of the fragment stage.
float rendered_tone_weight(float tone_weight) noexcept;

// A pair gain (pair_gain()) in the pair gain table's fixed point (MaterialTablesHeader::pair_gains), and
// a pair's three gains as the render pass reads them, for CPU twins of the fragment stage.
std::uint32_t pair_gain_units(float gain) noexcept;
std::array<float, 3> rendered_pair_gain(const Material& material, std::uint32_t light,
                                        std::uint32_t view) noexcept;

}  // namespace carbtf
