#include "scene/material_render.hpp"

#include "cli/cli_support.hpp"

namespace carbtf::cli {

MaterialRender prepare_material_render(Context& context, const Material& material, const SubspaceSynthesizer& synthesizer,
                                       std::uint64_t seed, float parallax_scale, std::uint32_t width, std::uint32_t height,
                                       const Mesh& mesh) {
  MaterialRender out;
  MaterialBindingInfo info;
  info.seed = seed;
  info.parallax_scale = parallax_scale;
  check(MaterialBinding::create(context, material, material_textures(synthesizer, material), info, out.binding), "cannot bind the material");
  check(out.binding->upload_and_wait(), "cannot upload the range map");
  RenderTargetInfo target;
  target.width = width;
  target.height = height;
  target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
  check(MeshRenderer::create(context, *out.binding, target, out.renderer), "cannot build the render pass");
  check(out.renderer->set_mesh(mesh), "cannot upload the mesh");
  return out;
}

}  // namespace carbtf::cli
