// `carbtf bench frame --parts`: what each part of the render pass's fragment stage costs. The pass is
// drawn again with one part replaced by a constant (MaterialBindingInfo::cost_probe), and with the other
// direction taps, frame by frame in turn with the full pass; prints and writes the table
// (write_frame_parts_report). Timing only: a replaced part makes the picture wrong.
#pragma once

#include <cstdint>
#include <filesystem>

#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/vulkan/context.hpp"
#include "carbtf/engine/vulkan/gpu_timer.hpp"

namespace carbtf::cli {

struct FramePartsSetup {
  Context& context;
  GpuTimer& timer;  // 2 timestamps or more
  const Material& material;
  MaterialTextures textures;  // resident subspace images, every one the frames need
  const RenderTargetInfo& target;
  const Mesh& mesh;
};

// `base`: the binding of the full pass. Frames orbit as bench frame's (orbiting_scene).
void run_frame_parts(const FramePartsSetup& setup, const MaterialBindingInfo& base, std::uint32_t frames,
                     std::uint32_t lights, const std::filesystem::path& out);

}  // namespace carbtf::cli
