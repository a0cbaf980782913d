// carbtf's own render pass: one mesh drawn with a MaterialBinding's material into an offscreen colour
// target (sRGB by default, or RGBA32F for exact comparisons), with depth, under up to
// CARBTF_RENDER_MAX_LIGHTS directional or point lights. It serves `carbtf render`, the demo and the
// benchmarks; a host engine draws with its own pipelines instead (material_binding.hpp).
//
// Use: create() once per target size; set_mesh(); record() into a command buffer of yours (after the
// binding's upload), or render() to submit, wait and read back.
// Lifetime: the renderer refers to the binding (which must outlive it); destroy it after the last
// command buffer it recorded into has finished, and before the Context.
// Thread safety: externally synchronized; one frame in flight (record() rewrites the frame uniforms).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/render_scene.hpp"
#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

struct RenderTargetInfo {
  std::uint32_t width = 1024;
  std::uint32_t height = 768;
  // VK_FORMAT_R8G8B8A8_SRGB (the shader's linear output encoded to sRGB) or VK_FORMAT_R32G32B32A32_SFLOAT.
  VkFormat colour_format = VK_FORMAT_R8G8B8A8_SRGB;
  std::array<float, 4> clear{0.04f, 0.04f, 0.05f, 0.0f};  // linear; alpha 0 marks background pixels
};

// A rendered frame read back: width * height pixels of `format`, row 0 at the top; RGBA8 bytes for
// the sRGB format, RGBA float32 otherwise.
struct RenderedImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::vector<std::uint8_t> bytes;
};

class MeshRenderer {
 public:
  static Status create(Context& context, const MaterialBinding& binding, const RenderTargetInfo& target,
                       std::unique_ptr<MeshRenderer>& out) noexcept;
  ~MeshRenderer();

  // Uploads a mesh (validate_mesh() must pass); replaces the previous one.
  Status set_mesh(const Mesh& mesh) noexcept;

  // Records the draw (clear, mesh) into the colour target, then its copy into the readback buffer.
  // The binding's upload must come first in execution order.
  Status record(VkCommandBuffer command_buffer, const RenderScene& scene) noexcept;
  // After the recorded work has finished: the frame.
  Status read_back(RenderedImage& out) const noexcept;
  // Convenience: record, submit, wait, read back.
  Status render(const RenderScene& scene, RenderedImage& out) noexcept;

  const RenderTargetInfo& target() const noexcept;

 private:
  MeshRenderer() = default;
  struct Resources;
  Context* context_ = nullptr;
  std::unique_ptr<Resources> resources_;
};

}  // namespace carbtf
