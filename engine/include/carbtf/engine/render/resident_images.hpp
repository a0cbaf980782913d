// A material's subspace images as a scene comes to need them: one RGBA32F layer per subspace image of
// the material, each filled when a frame first needs it by copying in a synthesis of only the new
// images. A frame that adds one image then costs that image's synthesis and a copy, not a synthesis of
// every resident image again. A MaterialBinding draws from textures(); after each record_add(),
// MaterialBinding::set_layers(material, layers()) lets it see the new images.
//
// Use: create(); record_transition() once before the first record_add() or draw; each frame,
// missing(needs.subspaces), and when some are missing: SubspaceSynthesizer::prepare() with exactly
// those, record() it, then record_add() in the same command buffer.
// Lifetime: destroy after the last command buffer that reads it has finished, and before the Context.
// Thread safety: externally synchronized.
#pragma once

#include <cstdint>
#include <memory>
#include <set>
#include <span>
#include <vector>

#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/status.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

class ResidentImages {
 public:
  // size x size texels per image (SynthesisBlock width and height), periodic when `periodic_overlap`
  // > 0, with up to `mip_levels` levels (0: all the size allows, material/mip_levels.hpp; 1: level 0
  // alone), which record_add() makes. invalid_argument for an empty size or a material without
  // subspace images.
  static Status create(Context& context, const Material& material, std::uint32_t size,
                       std::uint32_t periodic_overlap, std::unique_ptr<ResidentImages>& out,
                       std::uint32_t mip_levels = 0) noexcept;

  // Records the move of every layer to VK_IMAGE_LAYOUT_GENERAL, ready for fragment-shader reads.
  void record_transition(VkCommandBuffer command_buffer) const noexcept;

  // Of `needed`, the subspace images not resident yet, sorted, each once.
  std::vector<std::uint32_t> missing(std::span<const std::uint32_t> needed) const;

  // Records, after `synthesizer`'s recorded synthesis of at least `added`, the copy of their layers into
  // theirs and the blits that make their mip levels, ending visible to fragment-shader reads; they count as
  // resident from now. invalid_argument, recording nothing, when the synthesizer's images are of another size
  // or lack one of `added`.
  Status record_add(VkCommandBuffer command_buffer, const SubspaceSynthesizer& synthesizer,
                    std::span<const std::uint32_t> added) noexcept;

  // What a MaterialBinding draws: the array of every layer, with layers() as they stand.
  MaterialTextures textures() const;
  // Per subspace image: its layer when resident, else UINT32_MAX.
  std::vector<std::uint32_t> layers() const;
  std::size_t resident_count() const noexcept { return resident_.size(); }

 private:
  ResidentImages() = default;
  const Context* context_ = nullptr;
  Image image_;
  std::uint32_t subspaces_ = 0;
  std::uint32_t periodic_overlap_ = 0;
  std::set<std::uint32_t> resident_;
};

}  // namespace carbtf
