// The synthesized material made ready to draw: its binding (uploaded) and a render pass on a mesh into
// an RGBA32F target, as render, fidelity and demo all set them up.
#pragma once

#include <cstdint>
#include <memory>

#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/render/scene_pruning.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf::cli {

struct MaterialRender {
  std::unique_ptr<MaterialBinding> binding;  // outlives `renderer`, which uses it
  std::unique_ptr<MeshRenderer> renderer;
};

// After `synthesizer` has synthesized `material`'s subspace images. `hardware_filtering`:
// MaterialBindingInfo::hardware_filtering (false where the picture is scored, so that figures do not
// depend on the device's sampler precision); `coupling`: MaterialBindingInfo::pair_coupling;
// `parallax_steps`: MaterialBindingInfo::parallax_steps. Throws
// CommandError on failure.
MaterialRender prepare_material_render(Context& context, const Material& material,
                                       const SubspaceSynthesizer& synthesizer, std::uint64_t seed,
                                       float parallax_scale, std::uint32_t width, std::uint32_t height,
                                       const Mesh& mesh, bool hardware_filtering,
                                       PairCoupling coupling = PairCoupling::product,
                                       std::uint32_t parallax_steps = kDefaultParallaxSteps);

// The commands' scene pruner: the subspace images a frame's (light, view) pairs fall in, at the texel
// density of most of its pixels, up to 1024 texels a side (beyond that only on request, with
// --texture-size: 20 x 2048^2 takes 16 s on lavapipe). Throws CommandError on failure.
std::unique_ptr<ScenePruner> make_scene_pruner(const Material& material);

// Plans, records and runs one synthesis of `request` on `synthesizer`, waiting for it; the wall time in
// milliseconds. Throws CommandError on failure.
double timed_synthesis(Context& context, SubspaceSynthesizer& synthesizer, const Material& material,
                       const SynthesisRequest& request);

// What a frame synthesizes: images of width x height with every mip level (the render pass
// samples them), only the subspaces it needs where `prune`, and periodic where a closed mesh meets
// itself as u wraps (no seam there).
SynthesisRequest frame_synthesis_request(const SceneNeeds& needs, std::uint64_t seed, std::uint32_t width,
                                         std::uint32_t height, bool prune);

}  // namespace carbtf::cli
