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

// The render pass's colour under the relief (carbtf_material_shade()): the encoded luma (Rec. 601 over
// values to the power 1/2.4, about as a camera stores them) of `colour`, under the relief at the
// fragment's level, plus the encoded colour differences of `chroma_colour`, the same BTF under the relief
// RangeTiles::chroma_levels mip levels above; decoded. Linear RGB in and out.
std::array<float, 3> relief_chroma_mix(const std::array<float, 3>& colour,
                                       const std::array<float, 3>& chroma_colour) noexcept;

}  // namespace carbtf
