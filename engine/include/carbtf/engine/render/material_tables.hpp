// What the render pass reads of a material besides its subspace images, built on the host without Vulkan:
// the lookup tables (direction lookups and the pair table, as MaterialTablesHeader lays them out) and the
// relief (heights, tone, normals, horizons) of the window of the unbounded texture the textures hold.
// MaterialBinding uploads exactly these; the CPU reference of the render pass reads them too, so the two
// cannot drift apart.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/material/range_tiles.hpp"

namespace carbtf {

// Where each subspace image, or each (light, view) pair, lies among the layers the render pass samples.
// A layer of std::uint32_t max is not there; layers of 65535 or more do not fit the pair table.
struct MaterialLayers {
  std::vector<std::uint32_t> subspace_layers;  // [subspace]
  std::vector<std::uint32_t> pair_layers;      // [light * views + view]; when set, it wins
};

// The march's constants (carbtf_gpu_shared.h's CARBTF_PARALLAX_*, checked equal where the tables are
// built), for its CPU twin (reference/parallax_march.hpp).
inline constexpr float kParallaxStepTexels = 0.5f;
inline constexpr std::uint32_t kParallaxRefinements = 4;
inline constexpr float kParallaxMinViewZ = 0.05f;
inline constexpr std::uint32_t kDefaultParallaxSteps = 16;  // MaterialBindingInfo::parallax_steps' default

struct MaterialTablesInfo {
  std::uint32_t width = 0;  // of the subspace images
  std::uint32_t height = 0;
  bool wrap = false;                // periodic textures
  std::uint32_t mip_levels = 1;     // of the subspace images
  std::uint32_t relief_levels = 1;  // of the range map: mip_levels or more (MaterialTablesHeader)
  float parallax_scale = 1.0f;
  std::uint32_t lookup_grid_size = 0;                    // 0: DirectionLookupGrid's default
  std::uint32_t parallax_steps = kDefaultParallaxSteps;  // MaterialBindingInfo::parallax_steps
};

// The pair table's first words: per (light, view) pair its layer (low 16 bits) and its subspace's tone
// weight as a half float (high 16), at [2 * (light * views + view)].
void write_pair_table(const Material& material, const MaterialLayers& layers, std::span<std::uint32_t> out);

// A layer the pair table can hold: below CARBTF_PAIR_NO_LAYER, or none.
bool fits_pair_table(std::uint32_t layer);

// The relief of one window of the unbounded texture.
struct ReliefMaps {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool wrap = false;
  std::vector<float> heights;  // width * height, texels
  // 3 per texel: each colour channel's tone with its chroma applied, 1 + tone_chroma[c] * (plane - 1)
  // (material.hpp), so that a reader takes one factor per channel whether the tone has one plane or
  // three; 1 everywhere without a tone.
  std::vector<float> tone;
};

ReliefMaps relief_maps(const Material& material, const TextureWindow& block);

// What the parallax ray march needs of the heights (carbtf_parallax_uv): their mean (in double, rounded to
// float: the height the render pass reads is the height minus it), and the highest and lowest point,
// parallax_scale * (height - mean), where the march starts and where it ends.
struct ReliefExtent {
  float mean = 0.0f;
  float top = 0.0f;
  float bottom = 0.0f;
};
ReliefExtent relief_extent(std::span<const float> heights, float parallax_scale);

// The tables as RGBA32UI quads (MaterialTablesHeader first); `pair_table` receives the word offset of
// the pair table, which write_pair_table() rewrites when the layers change. The header's range mean is
// `relief`'s.
Status build_material_tables(const Material& material, const MaterialLayers& layers,
                             const MaterialTablesInfo& info, const ReliefMaps& relief,
                             std::vector<std::uint32_t>& tables, std::size_t& pair_table);

// Level 0 of the range texture's four RGBA32F layers, in the order the render pass reads them:
// 0: height (x) and tone (yzw); 1: relief normal (xyz, relief_normals.hpp; w left 0 for
// store_normal_lengths()); 2 and 3: the horizons of azimuths 0-3 and 4-7 (relief_horizons.hpp), 0 where
// the material casts no shadows.
inline constexpr std::uint32_t kRangeTextureLayers = 4;
std::vector<float> height_tone_texels(std::span<const float> heights, std::span<const float> tone);
std::vector<float> normal_texels(std::span<const float> heights, std::uint32_t width, std::uint32_t height,
                                 bool wrap);
// Both horizon layers' horizons (relief_horizons()), empty for a shadow scale of 0.
std::vector<float> relief_horizon_map(const ReliefMaps& relief, float shadow_scale);

}  // namespace carbtf
