#include "carbtf/engine/render/material_tables.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

#include <carbtf_gpu_shared.h>
#include <glm/gtc/packing.hpp>

#include "carbtf/engine/material/material_directions.hpp"
#include "carbtf/engine/render/relief_horizons.hpp"
#include "carbtf/engine/render/relief_normals.hpp"
#include "carbtf/engine/render/rendered_values.hpp"

static_assert(carbtf::kReliefAmbient == carbtf::gpu::CARBTF_RELIEF_AMBIENT,
              "the relit factor's ambient share differs between the C++ and GLSL");
static_assert(carbtf::kSpecularViewFloor == carbtf::gpu::CARBTF_SPECULAR_VIEW_FLOOR,
              "the specular lobe's view floor differs between the C++ and GLSL");

namespace carbtf {
namespace {

constexpr std::uint32_t kHeaderWords = sizeof(gpu::MaterialTablesHeader) / 4;
static_assert(kParallaxStepTexels == gpu::CARBTF_PARALLAX_STEP_TEXELS &&
                  kParallaxRefinements == gpu::CARBTF_PARALLAX_REFINEMENTS &&
                  kParallaxMinViewZ == gpu::CARBTF_PARALLAX_MIN_VIEW_Z,
              "the parallax march's CPU twin takes the shader's constants");
static_assert(kHeaderWords % 4 == 0, "the tables after the header start on a quad");

std::uint32_t float_bits(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// The quad (16 bytes, one texel of the tables' RGBA32UI view) at which `data` ends, padded to one.
std::uint32_t next_quad(std::vector<std::uint32_t>& data) {
  while (data.size() % 4 != 0) data.push_back(0u);
  return static_cast<std::uint32_t>(data.size() / 4);
}

// Appends one direction set's lookup (DirectionLookupGpu): each cell's entry range, then each entry
// inline with its directions' projections.
void append_lookup(const DirectionTriangulation& triangulation, const DirectionLookupGrid& grid,
                   std::vector<std::uint32_t>& data, gpu::DirectionLookupGpu& out) {
  out.count = static_cast<std::uint32_t>(triangulation.points.size());
  out.grid_size = grid.grid_size;
  out.cells = next_quad(data);
  for (std::size_t c = 0; c + 1 < grid.cell_starts.size(); ++c) {
    data.push_back(grid.cell_starts[c]);
    data.push_back(grid.cell_starts[c + 1]);
  }
  out.entries = next_quad(data);
  for (const std::uint32_t entry : grid.entries) {
    std::array<std::uint32_t, 3> index;
    if ((entry & gpu::CARBTF_LOOKUP_EDGE_BIT) == 0) {
      index = triangulation.triangles[entry];
    } else {
      const auto& edge = triangulation.boundary[entry & ~gpu::CARBTF_LOOKUP_EDGE_BIT];
      index = {edge[0], edge[1], edge[1]};
    }
    const std::size_t start = data.size();
    data.resize(start + 4 * gpu::CARBTF_LOOKUP_ENTRY_QUADS, 0u);
    data[start] = index[0] | (entry & gpu::CARBTF_LOOKUP_EDGE_BIT);
    data[start + 1] = index[1];
    data[start + 2] = index[2];
    for (std::size_t k = 0; k < 3; ++k) {
      data[start + 4 + 2 * k] = float_bits(static_cast<float>(triangulation.points[index[k]][0]));
      data[start + 5 + 2 * k] = float_bits(static_cast<float>(triangulation.points[index[k]][1]));
    }
  }
}

// The pair table's second words: the pair's gains on R, G and B in 10-bit fixed point (1 each for a
// material without gains, which multiplies by exactly 1).
void write_pair_gains(const Material& material, std::span<std::uint32_t> out) {
  for (std::uint32_t l = 0; l < material.lights.size(); ++l) {
    for (std::uint32_t v = 0; v < material.views.size(); ++v) {
      std::uint32_t word = 0;
      for (std::uint32_t c = 0; c < 3; ++c) {
        const float gain = material.pair_gains.empty() ? 1.0f : pair_gain(material, l, v, c);
        word |= pair_gain_units(gain) << (10 * c);
      }
      out[2 * (std::size_t{l} * material.views.size() + v) + 1] = word;
    }
  }
}

}  // namespace

bool fits_pair_table(std::uint32_t layer) {
  return layer < gpu::CARBTF_PAIR_NO_LAYER || layer == std::numeric_limits<std::uint32_t>::max();
}

void write_pair_table(const Material& material, const MaterialLayers& layers, std::span<std::uint32_t> out) {
  for (std::size_t l = 0; l < material.lights.size(); ++l) {
    for (std::size_t v = 0; v < material.views.size(); ++v) {
      const std::uint32_t s =
          subspace_of(material, static_cast<std::uint32_t>(l), static_cast<std::uint32_t>(v));
      const std::uint32_t layer = layers.pair_layers.empty()
                                      ? layers.subspace_layers[s]
                                      : layers.pair_layers[l * material.views.size() + v];
      const std::uint32_t field =
          layer == std::numeric_limits<std::uint32_t>::max() ? gpu::CARBTF_PAIR_NO_LAYER : layer;
      out[2 * (l * material.views.size() + v)] =
          field | std::uint32_t{glm::packHalf1x16(material.subspaces[s].tone_weight)} << 16;
    }
  }
}

Status build_material_tables(const Material& material, const MaterialLayers& layers,
                             const MaterialTablesInfo& info, const ReliefMaps& relief,
                             std::vector<std::uint32_t>& tables, std::size_t& pair_table) {
  tables.assign(kHeaderWords, 0u);
  gpu::MaterialTablesHeader header{};
  MaterialDirections directions;
  if (Status s = MaterialDirections::build(material, directions, info.lookup_grid_size); !s.ok()) return s;
  append_lookup(directions.light_triangulation(), directions.light_grid(), tables, header.lights);
  append_lookup(directions.view_triangulation(), directions.view_grid(), tables, header.views);
  header.pair_table = next_quad(tables);
  pair_table = tables.size();
  tables.resize(tables.size() + 2 * material.lights.size() * material.views.size());
  write_pair_table(material, layers, std::span(tables).subspan(pair_table));
  write_pair_gains(material, std::span(tables).subspan(pair_table));
  next_quad(tables);
  header.pair_gains = material.pair_gains.empty() ? 0u : 1u;
  header.width = info.width;
  header.height = info.height;
  header.parallax_scale = info.parallax_scale;
  header.light_z_floor = relight_floor(material);
  header.mip_levels = info.mip_levels;
  header.wrap = info.wrap ? 1u : 0u;
  header.shadows = material.range.shadow_scale > 0.0f ? 1u : 0u;
  header.specular_strength = material.range.specular_strength;
  header.specular_gloss = material.range.specular_gloss;
  header.specular_view_power = material.range.specular_view_power;
  const ReliefExtent extent = relief_extent(relief.heights, info.parallax_scale);
  header.range_mean = extent.mean;
  header.parallax_top = extent.top;
  header.parallax_bottom = extent.bottom;
  header.parallax_steps = info.parallax_steps;
  header.relief_levels = info.relief_levels;
  header.relief_chroma_levels = material.range.chroma_levels;
  header.tone_planes = static_cast<std::uint32_t>(tone_planes(material.range));
  std::memcpy(tables.data(), &header, sizeof header);
  return {};
}

ReliefExtent relief_extent(std::span<const float> heights, float parallax_scale) {
  ReliefExtent extent;
  if (heights.empty()) return extent;
  double sum = 0.0;
  for (float h : heights) sum += h;
  extent.mean = static_cast<float>(sum / static_cast<double>(heights.size()));
  const auto [low, high] = std::minmax_element(heights.begin(), heights.end());
  // The render pass's heights are these minus the mean, in float: the same subtraction bounds them.
  const float a = parallax_scale * (*high - extent.mean), b = parallax_scale * (*low - extent.mean);
  extent.top = std::max(a, b);  // a negative scale turns the relief over
  extent.bottom = std::min(a, b);
  return extent;
}

ReliefMaps relief_maps(const Material& material, const TextureWindow& block) {
  ReliefMaps relief;
  relief.width = block.width;
  relief.height = block.height;
  relief.wrap = block.periodic_overlap > 0;
  relief.heights.assign(std::size_t{block.width} * block.height, 0.0f);
  relief.tone.assign(3 * relief.heights.size(), 1.0f);
  if (material.range.tile_size == 0) return relief;
  enlarge_range_map(material.range, block, relief.heights);
  if (material.range.tone.empty()) return relief;
  std::vector<float> plane(relief.heights.size());
  for (std::size_t k = 0; k < 3; ++k) {
    if (k == 0 || tone_planes(material.range) == 3)
      enlarge_range_map(material.range, block, plane, tone_channel(k));
    const float chroma = material.range.tone_chroma[k];
    for (std::size_t i = 0; i < plane.size(); ++i) relief.tone[3 * i + k] = 1.0f + chroma * (plane[i] - 1.0f);
  }
  return relief;
}

std::vector<float> height_tone_texels(std::span<const float> heights, std::span<const float> tone) {
  std::vector<float> out(heights.size() * 4);
  for (std::size_t i = 0; i < heights.size(); ++i) {
    out[4 * i] = heights[i];
    for (std::size_t k = 0; k < 3; ++k) out[4 * i + 1 + k] = tone.empty() ? 1.0f : tone[3 * i + k];
  }
  return out;
}

std::vector<float> normal_texels(std::span<const float> heights, std::uint32_t width, std::uint32_t height,
                                 bool wrap) {
  std::vector<float> normals;
  relief_normals(heights, width, height, wrap, normals);
  std::vector<float> out(heights.size() * 4, 0.0f);
  for (std::size_t i = 0; i < heights.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) out[4 * i + k] = normals[3 * i + k];
  }
  return out;
}

std::vector<float> relief_horizon_map(const ReliefMaps& relief, float shadow_scale) {
  std::vector<float> horizons;
  if (shadow_scale > 0.0f)
    relief_horizons(relief.heights, relief.width, relief.height, relief.wrap, shadow_scale, horizons);
  return horizons;
}

}  // namespace carbtf
