#include "bench/frame_pass.hpp"

#include <cstdio>
#include <vector>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/sample/sample_btf.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "cli/cli_support.hpp"

namespace carbtf::cli {

Material material_or_leather_sample(const std::string& path, OwnedFolder& out) {
  Material material;
  if (!path.empty()) {
    check(read_material_file(path, material), "cannot read the material");
    return material;
  }
  std::printf("no --material: analysing the leather sample (64^2) into %s\n",
              (out.root() / "leather.cbtf").c_str());
  std::fflush(stdout);
  const Surface surface = make_sample_surface("leather", 64, 1);
  const std::filesystem::path btf = out.claim("leather_btf");
  write_sample_btf(surface, btf, ".png", false);
  std::vector<std::string> warnings;
  AnalysisOptions analysis;
  analysis.progress = false;
  material = analyze_btf(load_btf(btf, {}, warnings), analysis).material;
  check(write_material_file(out.root() / "leather.cbtf", material), "cannot write the material");
  out.release(btf);
  return material;
}

FramePass make_frame_pass(Context& context, const Material& material, const Mesh& mesh,
                          const RenderTargetInfo& target, std::uint32_t texture_size, std::uint32_t overlap,
                          const MaterialBindingInfo& info) {
  FramePass pass;
  check(ResidentImages::create(context, material, texture_size, overlap, pass.resident, info.max_mip_levels),
        "cannot hold the images");
  check(MaterialBinding::create(context, material, pass.resident->textures(), info, pass.binding),
        "cannot bind");
  check(context.submit_and_wait([&](VkCommandBuffer cb) {
    pass.resident->record_transition(cb);
    return pass.binding->record_upload(cb);
  }),
        "cannot upload the material");
  check(MeshRenderer::create(context, *pass.binding, target, pass.renderer), "cannot build the render pass");
  check(pass.renderer->set_mesh(mesh), "cannot upload the mesh");
  return pass;
}

}  // namespace carbtf::cli
