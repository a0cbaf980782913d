// The synthesized material made ready to draw: its binding (uploaded) and a render pass on a mesh into
// an RGBA32F target, as render, fidelity and demo all set them up.
#pragma once

#include <cstdint>
#include <memory>

#include "carbtf/engine/context.hpp"
#include "carbtf/engine/material_binding.hpp"
#include "carbtf/engine/mesh.hpp"
#include "carbtf/engine/mesh_renderer.hpp"
#include "carbtf/engine/subspace_synthesizer.hpp"

namespace carbtf::cli {

struct MaterialRender {
  std::unique_ptr<MaterialBinding> binding;  // outlives `renderer`, which uses it
  std::unique_ptr<MeshRenderer> renderer;
};

// After `synthesizer` has synthesized `material`'s subspace images. Throws CommandError on failure.
MaterialRender prepare_material_render(Context& context, const Material& material, const SubspaceSynthesizer& synthesizer,
                                       std::uint64_t seed, float parallax_scale, std::uint32_t width, std::uint32_t height,
                                       const Mesh& mesh);

}  // namespace carbtf::cli
