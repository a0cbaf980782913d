#include "scene/material_render.hpp"

#include <chrono>

#include "cli/cli_support.hpp"

namespace carbtf::cli {

MaterialRender prepare_material_render(Context& context, const Material& material,
                                       const SubspaceSynthesizer& synthesizer, std::uint64_t seed,
                                       float parallax_scale, std::uint32_t width, std::uint32_t height,
                                       const Mesh& mesh, bool hardware_filtering, PairCoupling coupling,
                                       std::uint32_t parallax_steps) {
  MaterialRender out;
  MaterialBindingInfo info;
  info.seed = seed;
  info.parallax_scale = parallax_scale;
  info.hardware_filtering = hardware_filtering;
  info.pair_coupling = coupling;
  info.parallax_steps = parallax_steps;
  check(
      MaterialBinding::create(context, material, material_textures(synthesizer, material), info, out.binding),
      "cannot bind the material");
  check(out.binding->upload_and_wait(), "cannot upload the range map");
  RenderTargetInfo target;
  target.width = width;
  target.height = height;
  target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
  check(MeshRenderer::create(context, *out.binding, target, out.renderer), "cannot build the render pass");
  check(out.renderer->set_mesh(mesh), "cannot upload the mesh");
  return out;
}

double timed_synthesis(Context& context, SubspaceSynthesizer& synthesizer, const Material& material,
                       const SynthesisRequest& request) {
  const auto begin = std::chrono::steady_clock::now();
  check(synthesizer.prepare(material, request), "cannot plan the synthesis");
  check(context.submit_and_wait([&](VkCommandBuffer cb) { return synthesizer.record(cb); }),
        "synthesis failed");
  return seconds_since(begin) * 1e3;
}

std::unique_ptr<ScenePruner> make_scene_pruner(const Material& material) {
  PruningOptions pruning;
  pruning.max_texture_size = 1024;
  std::unique_ptr<ScenePruner> pruner;
  check(ScenePruner::create(material, pruning, pruner), "cannot prune scenes of this material");
  return pruner;
}

SynthesisRequest frame_synthesis_request(const SceneNeeds& needs, std::uint64_t seed, std::uint32_t width,
                                         std::uint32_t height, bool prune) {
  SynthesisRequest request;
  request.seed = seed;
  request.width = width;
  request.height = height;
  request.mip_levels = 0;
  if (prune) request.subspaces = needs.subspaces;
  if (needs.periodic) request.periodic_overlap = default_periodic_overlap(request.width, request.height);
  return request;
}

}  // namespace carbtf::cli
