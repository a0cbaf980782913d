// The render pass's fragment stage (compute_shaders/include/carbtf_material.glsl) on the CPU, for the
// built-in plane (make_plane(), z = 0, identity model): each pixel centre's ray meets the plane
// analytically, then parallax, range-map normal, 9-weight interpolation and relighting follow the
// shader's order. Its direction weights come from the triangulation search (pair_weights), not from
// the GPU's lookup grids, so a test against it checks those grids too.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/render/material_tables.hpp"
#include "carbtf/engine/render/render_scene.hpp"
#include "carbtf/engine/synthesis/synthesis_request.hpp"

namespace carbtf::reference {

struct ReferenceRenderInput {
  const Material* material = nullptr;
  const SynthesizedImages* images = nullptr;  // the subspace images (host copies); unsynthesized ones empty
  // The relief as MaterialBinding uploads it (relief_maps(), material_tables.hpp): images->width *
  // images->height heights in texels, and 3 tone factors per texel, each colour channel's with its chroma
  // applied (or empty: 1 everywhere).
  std::span<const float> range_map;
  std::span<const float> tone_map;
  float parallax_scale = 1.0f;
  std::uint32_t parallax_steps =
      kDefaultParallaxSteps;  // MaterialBindingInfo::parallax_steps (0: offset mapping)
  // Mip levels to filter with, level 0 included (MaterialBinding::mip_levels()): the reference builds
  // them as the means of 2 x 2 texels (mip_chain.hpp) and picks each pixel's level of detail from the
  // uv of its 2 x 2 quad's neighbours, as the fragment stage's fine derivatives do. 1: level 0 only.
  std::uint32_t mip_levels = 1;
  // Mip levels of the relief (MaterialBinding::relief_levels()); 0: mip_levels + RangeTiles::chroma_levels
  // where the size allows, as the binding makes them on a device that filters RGBA32F.
  std::uint32_t relief_levels = 0;
  // The normal as the render pass computed it before normals were stored: per pixel, the central
  // differences of the bilinear heights one texel apart, normalised (level 0 only). The tests bound
  // what storing them changed (relief_normals.hpp).
  bool normals_from_heights = false;
  // The textures tile (a periodic synthesis): texel addresses wrap instead of repeating the edge.
  bool wrap = false;
  // How the light's and the view's weights combine (MaterialBindingInfo::pair_coupling).
  PairCoupling pair_coupling = PairCoupling::product;
};

// width * height RGBA floats, row 0 at the top: linear colour and alpha 1 where the plane covers the
// pixel centre, `clear` elsewhere. Throws std::invalid_argument for inconsistent inputs.
std::vector<float> render_plane(const ReferenceRenderInput& input, const RenderScene& scene,
                                std::uint32_t width, std::uint32_t height, std::array<float, 4> clear);

}  // namespace carbtf::reference
