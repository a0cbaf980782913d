// What `carbtf bench frame` draws with: the material to bench (a file, or the leather sample analysed
// on the spot) and the render pass its first frame sets up (resident images, binding, renderer).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/render/resident_images.hpp"
#include "carbtf/engine/vulkan/context.hpp"
#include "cli/owned_folder.hpp"

namespace carbtf::cli {

// The material file at `path`, or with an empty path the leather sample (64^2) analysed into
// OUT/leather.cbtf (its scratch BTF released when done). CommandError on failure.
Material material_or_leather_sample(const std::string& path, OwnedFolder& out);

struct FramePass {
  std::unique_ptr<ResidentImages> resident;  // no image yet: frames add what they need
  std::unique_ptr<MaterialBinding> binding;
  std::unique_ptr<MeshRenderer> renderer;
};

// Images of texture_size^2 (with `overlap` where periodic, every mip level `info` asks for), bound and
// uploaded, and a renderer of `mesh` into `target`. CommandError on failure.
FramePass make_frame_pass(Context& context, const Material& material, const Mesh& mesh,
                          const RenderTargetInfo& target, std::uint32_t texture_size, std::uint32_t overlap,
                          const MaterialBindingInfo& info);

}  // namespace carbtf::cli
