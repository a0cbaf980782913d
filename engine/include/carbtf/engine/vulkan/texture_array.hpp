// Host images uploaded into a sampled 2D-array image: for instance the measured BTF images of the
// (light, view) pairs a frame needs, drawn through a MaterialBinding beside the model
// (MaterialTextures::pair_layers), or a material's enlarged range map and relief tone. RGBA8 (sRGB or UNORM),
// R32F, RG32F or RGBA32F texels.
//
// Use: create(); set_layer() for every layer (host memory, staged); record_upload() into a command
// buffer of yours, or upload_and_wait(). The image ends in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL.
// It has up to `mip_levels` levels (0: all of mip_level_count(), material/mip_levels.hpp), where the
// device blits the format with a linear filter; else one. The upload fills them by blits, or, created
// with `host_levels`, copies the levels the caller gave with set_level() (for texels whose level
// above is not the mean of the level below in every channel).
// Lifetime: destroy after the last command buffer that reads it has finished, and before the Context.
// Thread safety: externally synchronized.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "carbtf/engine/status.hpp"
#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

class TextureArray {
 public:
  // invalid_argument for another format, an empty size, or more layers than the device allows.
  static Status create(Context& context, std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                       VkFormat format, std::unique_ptr<TextureArray>& out, std::uint32_t mip_levels = 1,
                       bool host_levels = false) noexcept;
  ~TextureArray();

  // Copies one layer, width * height texels row-major, into the staging memory.
  Status set_layer(std::uint32_t layer, std::span<const std::uint8_t> texels) noexcept;
  // Copies level `level` (> 0) of one layer, (width >> level) * (height >> level) texels row-major, into
  // the staging memory; only for an array created with `host_levels`, which then needs every level.
  Status set_level(std::uint32_t layer, std::uint32_t level, std::span<const std::uint8_t> texels) noexcept;
  Status record_upload(VkCommandBuffer command_buffer) const noexcept;
  Status upload_and_wait() noexcept;

  VkImageView view() const noexcept { return image_.view(); }
  std::uint32_t width() const noexcept { return image_.info().width; }
  std::uint32_t height() const noexcept { return image_.info().height; }
  std::uint32_t layers() const noexcept { return image_.info().array_layers; }
  std::uint32_t mip_levels() const noexcept { return image_.info().mip_levels; }

 private:
  TextureArray() = default;
  Context* context_ = nullptr;
  Image image_;
  Buffer staging_;  // every layer's level 0, then (host_levels) every layer's level 1, and so on
  std::uint32_t texel_bytes_ = 0;
  bool host_levels_ = false;
  // Byte offset of `level` of `layer` in the staging memory.
  std::size_t staging_offset(std::uint32_t layer, std::uint32_t level) const noexcept;
};

}  // namespace carbtf
