#include "scene/measured_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/vulkan/texture_array.hpp"
#include "cli/cli_support.hpp"
#include "report/pictures.hpp"

namespace carbtf::cli {

RenderedImage render_measured(Context& context, const Material& material, const BtfDataset& dataset,
                              const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                              const Mesh& mesh, const RenderScene& scene, const RenderTargetInfo& target,
                              std::uint32_t mip_levels, PairCoupling coupling) {
  const std::uint32_t w = dataset.width(), h = dataset.height();
  const double bytes = static_cast<double>(pairs.size()) * w * h * 4;
  if (bytes > 1.5 * 1024 * 1024 * 1024) {
    throw CommandError("the frame needs " + std::to_string(pairs.size()) +
                       " measured images, more than 1.5 GiB; use a smaller view of the mesh");
  }
  const std::uint32_t layer_limit = context.device_info().max_image_array_layers;
  if (pairs.size() > layer_limit) {
    throw CommandError("the frame can use " + std::to_string(pairs.size()) +
                       " measured (light, view) pairs, more than the " + std::to_string(layer_limit) +
                       " layers a texture array holds on " + context.device_info().name +
                       "; compare on a plane or a narrower view (--fov), which use fewer pairs");
  }
  std::unique_ptr<TextureArray> array;
  check(
      TextureArray::create(context, w, h, static_cast<std::uint32_t>(std::max<std::size_t>(pairs.size(), 1)),
                           VK_FORMAT_R8G8B8A8_SRGB, array, mip_levels),
      "cannot hold the measured images");
  MaterialTextures textures;
  textures.view = array->view();
  textures.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  // Mip levels of the measurement too, so that a foreshortened view filters it as it filters the model.
  textures.mip_levels = array->mip_levels();
  textures.width = w;
  textures.height = h;
  textures.pair_layers.assign(material.lights.size() * material.views.size(), UINT32_MAX);
  std::vector<float> linear(std::size_t{w} * h * 3);
  std::vector<std::uint8_t> texels(std::size_t{w} * h * 4, 255);
  std::uint32_t layer = 0;
  for (const auto& [light, view] : pairs) {
    if (!dataset.has_image({light, view})) continue;
    dataset.linear_rgb({light, view}, linear);
    for (std::size_t p = 0; p < std::size_t{w} * h; ++p) {
      for (int k = 0; k < 3; ++k) {
        texels[4 * p + k] = linear_to_srgb8(linear[3 * p + k]);
      }
    }
    check(array->set_layer(layer, texels), "cannot stage a measured image");
    textures.pair_layers[std::size_t{light} * material.views.size() + view] = layer++;
  }
  check(array->upload_and_wait(), "cannot upload the measured images");
  // The measurement as it is: no relief, and none of the model's corrections of its pairs' colours.
  Material flat = material;
  flat.range = {};
  flat.pair_gains = {};
  MaterialBindingInfo info;
  info.parallax_scale = 0.0f;
  info.hardware_filtering = false;  // filtered by hand, as the model beside it where it is scored
  info.pair_coupling = coupling;
  std::unique_ptr<MaterialBinding> binding;
  check(MaterialBinding::create(context, flat, textures, info, binding), "cannot bind the measured images");
  check(binding->upload_and_wait(), "cannot upload the flat range map");
  std::unique_ptr<MeshRenderer> renderer;
  check(MeshRenderer::create(context, *binding, target, renderer), "cannot build the render pass");
  check(renderer->set_mesh(mesh), "cannot upload the mesh");
  RenderedImage frame;
  check(renderer->render(scene, frame), "rendering the measured BTF failed");
  return frame;
}

void write_measured_comparison(Context& context, const Material& material, const BtfDataset& dataset,
                               const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                               const Mesh& mesh, const RenderScene& scene,
                               const std::vector<float>& model_rgb, std::uint32_t width, std::uint32_t height,
                               const std::filesystem::path& out, PairCoupling coupling) {
  std::printf("rendering the measured BTF (%zu of its images) on the same mesh\n", pairs.size());
  std::fflush(stdout);
  RenderTargetInfo target;
  target.width = width;
  target.height = height;
  target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
  const std::vector<float> measured =
      rendered_rgb(render_measured(context, material, dataset, pairs, mesh, scene, target, 0, coupling));
  check_validation(context);
  const std::filesystem::path measured_path = with_stem_suffix(out, "_measured"),
                              compare_path = with_stem_suffix(out, "_compare");
  write_rgb_image(measured_path, measured, width, height, true);
  write_rgb_image(compare_path, side_by_side(model_rgb, measured, width, height), 2 * width, height, true);
  std::printf("wrote %s (measured) and %s (model | measured)\n", measured_path.string().c_str(),
              compare_path.string().c_str());
}

}  // namespace carbtf::cli
