// What a fragment shader needs to draw a synthesized material: one descriptor set (layout in
// carbtf_gpu_shared.h, "Material render pass") holding the subspace images, the enlarged range map and
// the lookup tables of compute_shaders/include/carbtf_material.glsl. A host engine puts set_layout()
// into its own pipeline layout at the set index it compiles the include with (CARBTF_MATERIAL_SET),
// binds set() and calls carbtf_material_shade() in its own fragment shader.
//
// Use: create() after the subspace images exist (SubspaceSynthesizer::prepare()); then record_upload()
// into a command buffer of yours (or upload_and_wait()) once, before the first draw that binds set().
//
// Lifetime: the binding refers to the subspace image view it was given (it does not own it; the
// synthesizer must stay alive and not be prepared again while the set is in use) and owns everything
// else. Destroy it after the last command buffer that binds its set has finished, and before the
// Context. Thread safety: externally synchronized; set() may be bound from any thread once uploaded.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/render/material_tables.hpp"  // the parallax march's default
#include "carbtf/engine/render/rendered_values.hpp"  // the CPU twin of what the pass reads
#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

class SubspaceSynthesizer;

// The synthesized subspace images a binding reads.
struct MaterialTextures {
  VkImageView view = VK_NULL_HANDLE;  // RGBA32F 2D-array view, one layer per synthesized subspace image
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;  // the layout the images are in when drawn
  // Mip levels of `view`, level 0 included, each the mean of 2 x 2 texels of the one below
  // (material/mip_levels.hpp; SynthesisRequest::mip_levels, ResidentImages and TextureArray make them).
  // The render pass samples them (and as many of the range map's); 1: level 0 alone.
  std::uint32_t mip_levels = 1;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  // > 0: the images tile (SynthesisBlock::periodic_overlap); the range map is then made periodic too
  // and the render pass wraps texel addresses instead of repeating the edge texels.
  std::uint32_t periodic_overlap = 0;
  // Per subspace of the material: its layer, or UINT32_MAX when it was not synthesized (pairs that
  // fall there then contribute nothing).
  std::vector<std::uint32_t> layers;
  // Instead of `layers` when not empty: the layer of every (light, view) pair, [light * views + view],
  // or UINT32_MAX. Measured images (one per pair, TextureArray) are drawn this way.
  std::vector<std::uint32_t> pair_layers;
};

// The textures of a prepared synthesizer.
MaterialTextures material_textures(const SubspaceSynthesizer& synthesizer, const Material& material);

// MaterialBindingInfo::cost_probe's bits (carbtf_gpu_shared.h's CARBTF_COST_PROBE_*): each replaces one
// part of carbtf_material.glsl's fragment stage by a constant.
namespace cost_probe {
constexpr std::uint32_t lookups = 1;         // the two direction lookups: fixed weights
constexpr std::uint32_t pair_reads = 2;      // the pair table: layers from the indices, gains 1
constexpr std::uint32_t subspace_reads = 4;  // the 9 subspace image reads: a grey per layer
constexpr std::uint32_t relief = 8;          // the normal, tone and horizons: flat, 1, none
constexpr std::uint32_t parallax = 16;       // the parallax ray march: no shift
}  // namespace cost_probe

// MaterialBindingInfo::parallax_steps' limit.
inline constexpr std::uint32_t kMaxParallaxSteps = 256;

struct MaterialBindingInfo {
  // The range map's block of its enlarged map: the synthesized block's seed and position, so that the
  // range map and the subspace images describe the same surface.
  std::uint64_t seed = 0;
  std::int64_t row0 = 0;
  std::int64_t col0 = 0;
  // Parallax offset per texel of height (1: the range map's own scale; 0: no parallax).
  float parallax_scale = 1.0f;
  // The parallax ray march's most steps down the view ray (carbtf_parallax_uv), besides its 5 reads that
  // refine the hit: a step moves at most half a texel across or down, so 16 reach a relief 4.6 texels
  // deep at 60 degrees from the top (deeper ones, or views nearer grazing, take longer steps). 0: offset
  // mapping, one height read per fragment, which leaves facets turned away from the view in sight
  // (docs/design.md 4.6). At most 256.
  std::uint32_t parallax_steps = kDefaultParallaxSteps;
  // Cells per side of each direction lookup grid (MaterialDirections).
  std::uint32_t lookup_grid_size = 64;
  // At most this many mip levels, level 0 included (0: as many as the textures allow, mip_levels.hpp;
  // 1: level 0 alone, the cheapest render pass, which aliases where a texel is smaller than a pixel).
  std::uint32_t max_mip_levels = 0;
  // Read the subspace images and the range texture's heights, tone and horizons through a trilinear
  // sampler (carbtf_material.glsl's hardware filtering) where the device filters RGBA32F linearly: the
  // fast path, within the device's sub-texel precision of the hand filtering. false: a sampler that does not
  // filter, for hosts that compare the render with the CPU twin (render_reference.hpp) bit for bit or nearly.
  bool hardware_filtering = true;
  // How the light's and the view's weights combine into (light, view) pair weights
  // (direction_interpolation.hpp): the paper's 9 pairs, or the staircase's 5, which reads 5 subspace
  // images per light instead of 9 (a 1920x1080 sphere's render pass on lavapipe about a fifth faster)
  // and draws another picture between the measured directions (docs/design.md 4.5).
  PairCoupling pair_coupling = PairCoupling::product;
  // For benchmarks only (`carbtf bench frame --parts`): cost_probe bits, each part of the fragment stage
  // they name replaced by a constant, the picture wrong. 0: the material.
  std::uint32_t cost_probe = 0;
};

// The values of carbtf_material.glsl's specialization constants that suit one binding, at their default
// ids (CARBTF_SHADOWS_DEFAULT_CONSTANT_ID, CARBTF_HARDWARE_FILTERING_DEFAULT_CONSTANT_ID,
// CARBTF_COST_PROBE_DEFAULT_CONSTANT_ID, CARBTF_PAIR_COUPLING_DEFAULT_CONSTANT_ID): a fragment
// stage's pSpecializationInfo = &constants.info. Self-referencing: keep the object where it is (no copy
// or move) until the pipeline is created.
struct MaterialShaderConstants {
  std::array<std::uint32_t, 4> values{};  // two VkBool32, the cost probe's bits, the pair coupling
  std::array<VkSpecializationMapEntry, 4> entries{};
  VkSpecializationInfo info{};
};

class MaterialBinding {
 public:
  // Builds the lookup tables and the enlarged range map on the host and the GPU objects to hold them.
  // invalid_argument when the textures do not match the material (layers per subspace, size).
  static Status create(Context& context, const Material& material, const MaterialTextures& textures,
                       const MaterialBindingInfo& info, std::unique_ptr<MaterialBinding>& out) noexcept;
  ~MaterialBinding();

  // Points the material's subspace images at other layers of the same textures (MaterialTextures::layers;
  // UINT32_MAX: not there, pairs that fall there contribute nothing), for a host that fills a texture
  // array over time, one newly needed subspace image at a time. `material` is the binding's own. No
  // GPU work that reads the binding may be in flight: the table is host memory the fragment stage reads.
  // invalid_argument for a binding of pair layers or a layer list of another length.
  Status set_layers(const Material& material, std::span<const std::uint32_t> layers) noexcept;

  // Records the range map's upload, with its mip levels, and its transition for fragment-shader reads.
  Status record_upload(VkCommandBuffer command_buffer) const noexcept;
  // Levels of the subspace images the render pass samples, level 0 included.
  std::uint32_t mip_levels() const noexcept;
  // Mip levels of the range texture: mip_levels() + RangeTiles::chroma_levels where its size and the
  // device allow, so that the relief's chroma is read that many levels above its brightness
  // (carbtf_material_shade()).
  std::uint32_t relief_levels() const noexcept;
  // Whether the material's relief casts shadows (RangeTiles::shadow_scale): a pipeline that draws only
  // materials without may set carbtf_material.glsl's specialization constant CARBTF_SHADOWS_CONSTANT_ID
  // (1000 by default) to false, which saves the horizon reads (on lavapipe a fifth of a sphere frame's render
  // pass).
  bool casts_shadows() const noexcept;
  // Whether the binding's sampler filters (MaterialBindingInfo::hardware_filtering, where the device
  // can): a pipeline may then set carbtf_material.glsl's specialization constant
  // CARBTF_HARDWARE_FILTERING_CONSTANT_ID (1001 by default) to true, which reads each of the 9 taps, the
  // height, the tone and the horizons once instead of 8 texels by hand (on lavapipe a fifth to a quarter
  // of a sphere frame's render pass).
  bool hardware_filtering() const noexcept;
  // MaterialBindingInfo::pair_coupling: a pipeline sets carbtf_material.glsl's specialization constant
  // CARBTF_PAIR_COUPLING_CONSTANT_ID (1003 by default) to match (shader_constants() does).
  PairCoupling pair_coupling() const noexcept;
  // The constants above for a pipeline that draws this material (or materials whose bindings agree).
  void shader_constants(MaterialShaderConstants& out) const noexcept;
  // Convenience: record_upload() through the context's submit-and-wait.
  Status upload_and_wait() noexcept;

  VkDescriptorSetLayout set_layout() const noexcept;
  VkDescriptorSet set() const noexcept;
  std::uint32_t width() const noexcept;
  std::uint32_t height() const noexcept;

  // The tables exactly as uploaded (MaterialTablesHeader, then the data), for CPU twins and tests.
  const std::vector<std::uint32_t>& tables() const noexcept;
  // The enlarged range map as uploaded: width() * height() heights in texels, row-major.
  const std::vector<float>& range_map() const noexcept;
  // The enlarged relief tone as uploaded: 3 floats per texel, the factor's tone of each colour channel
  // (R, G, B) with its chroma applied (RangeTiles::tone_chroma), 1 everywhere for a material without one.
  const std::vector<float>& tone_map() const noexcept;

 private:
  MaterialBinding() = default;
  struct Resources;
  Context* context_ = nullptr;
  std::unique_ptr<Resources> resources_;
};

}  // namespace carbtf
