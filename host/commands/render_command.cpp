// `carbtf render material.cbtf --mesh sphere --out frame.png`: the material synthesized on the GPU and
// drawn on a mesh by the render pass (parallax, 9-weight interpolation, relit range map), headless.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/render/scene_pruning.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "report/pictures.hpp"
#include "scene/material_render.hpp"
#include "scene/measured_render.hpp"
#include "scene/orbit.hpp"
#include "scene/scene_mesh.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  DeviceOptions device;
  std::string material;
  std::string mesh = "sphere";
  std::vector<double> camera{60.0, 35.0, 3.6};  // theta, phi (degrees), distance
  float fov = 40.0f;
  std::vector<std::vector<double>> lights;        // theta, phi[, intensity]
  std::vector<std::vector<double>> point_lights;  // x, y, z[, intensity]
  std::string size = "1024x768";
  std::uint32_t texture_size = 0;  // 0: what the frame needs
  bool prune = true;
  bool measure_savings = false;
  std::uint64_t seed = 1;
  float parallax = 1.0f;
  std::uint32_t parallax_steps = kDefaultParallaxSteps;
  bool hand_filtering = false;
  PairCoupling pair_coupling = PairCoupling::product;
  std::string out = "frame.png";
  std::string compare;  // a measured BTF to render beside the model
};

void run_render(const RenderOptions& options) {
  std::uint32_t width = 0, height = 0;
  parse_frame_size(options.size, "--size", width, height);
  check_image_output_path(options.out, "--out");
  Material material;
  check(read_material_file(options.material, material), "cannot read the material");
  Mesh mesh = load_mesh(options.mesh);
  const RenderScene scene =
      scene_from_options(options.camera, options.fov, options.lights, options.point_lights);
  std::optional<BtfDataset> measured;
  if (!options.compare.empty()) {
    measured = load_measurement_of(material, options.compare, "--compare");
  }

  auto context = make_context(options.device);
  // Only what the frame can use: the subspace images its (light, view) pairs fall in.
  const std::unique_ptr<ScenePruner> pruner = make_scene_pruner(material);
  SceneNeeds needs;
  check(pruner->needs(mesh, scene, width, height, needs), "cannot work out what the scene needs");
  // Beside a measurement, the model at the measurement's scale: one texel per measured pixel.
  std::uint32_t texture_width = options.texture_size ? options.texture_size : needs.texture_size;
  std::uint32_t texture_height = texture_width;
  if (measured && !options.texture_size)
    texture_width = measured->width(), texture_height = measured->height();
  const SynthesisRequest request =
      frame_synthesis_request(needs, options.seed, texture_width, texture_height, options.prune);
  const std::size_t synthesized = options.prune ? needs.subspaces.size() : material.subspaces.size();
  std::printf("[1/3] synthesizing %zu of %zu subspace images of %ux%u on %s\n", synthesized,
              material.subspaces.size(), request.width, request.height, context->device_info().name.c_str());
  std::fflush(stdout);
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
  auto synthesize = [&](const SynthesisRequest& r) {
    return timed_synthesis(*context, *synthesizer, material, r);
  };
  double full_ms = 0.0;
  if (options.measure_savings && options.prune) {
    // The pruned request once first, so that neither timed run pays the first dispatch's warm-up.
    synthesize(request);
    SynthesisRequest full = request;
    full.subspaces.clear();
    full_ms = synthesize(full);
  }
  const double synthesis_ms = synthesize(request);
  std::printf(
      "synthesized %zu of %zu subspace images (%zu light-view pairs in view), %.1f Mtexels, in %.1f ms\n",
      synthesized, material.subspaces.size(), needs.pairs.size(),
      static_cast<double>(synthesized) * request.width * request.height * 1e-6, synthesis_ms);
  if (full_ms > 0.0) {
    std::printf("all %zu would take %.1f ms: pruning saved %.1f ms (%.1fx)\n", material.subspaces.size(),
                full_ms, full_ms - synthesis_ms, full_ms / synthesis_ms);
  }

  std::printf("[2/3] range map, lookup tables and render pipeline\n");
  std::fflush(stdout);
  const MaterialRender model =
      prepare_material_render(*context, material, *synthesizer, options.seed, options.parallax, width, height,
                              mesh, !options.hand_filtering, options.pair_coupling, options.parallax_steps);

  std::printf("[3/3] rendering %ux%u, %zu triangles, %zu light(s)\n", width, height, mesh.indices.size() / 3,
              scene.lights.size());
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  RenderedImage frame;
  check(model.renderer->render(scene, frame), "rendering failed");
  const double render_ms = seconds_since(start) * 1e3;
  check_validation(*context);

  const std::vector<float> rgb = rendered_rgb(frame);
  require_finite(rgb, options.material + ": rendered frame");
  const fs::path out = options.out;
  if (out.has_parent_path()) create_folder(out.parent_path());
  write_rgb_image(out, rgb, width, height, true);
  if (measured)
    write_measured_comparison(*context, material, *measured, needs.pairs, mesh, scene, rgb, width, height,
                              out, options.pair_coupling);
  std::printf("synthesis %.1f ms, render %.1f ms (wall, with readback)\nwrote %s\n", synthesis_ms, render_ms,
              out.string().c_str());
}

}  // namespace

void register_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand("render",
                                         "Render a material on a mesh, headless: GPU synthesis, then "
                                         "parallax occlusion mapping with the 9-weight "
                                         "interpolation of the subspace images, relit by the range map");
  command->add_option("material", options->material, "Material file (.cbtf) from `carbtf analyze`")
      ->required();
  command
      ->add_option("--mesh", options->mesh,
                   "plane, sphere, cylinder, torus, or an OBJ file with texture coordinates")
      ->capture_default_str();
  command
      ->add_option(
          "--camera", options->camera,
          "Camera orbit THETA,PHI[,DISTANCE]: elevation from +z and azimuth in degrees, distance from the "
          "origin; it looks at the origin")
      ->delimiter(',')
      ->expected(2, 3)
      ->capture_default_str();
  command
      ->add_option("--fov", options->fov, "Vertical field of view in degrees; 0 gives an orthographic camera")
      ->check(CLI::Range(0.0f, 170.0f))
      ->capture_default_str();
  command
      ->add_option("--light", options->lights,
                   "Directional light THETA,PHI[,INTENSITY] in degrees, towards the light; repeat for more "
                   "(default: one at 45,120)")
      ->delimiter(',')
      ->expected(2, 3)
      ->allow_extra_args(false);
  command
      ->add_option("--point-light", options->point_lights,
                   "Point light X,Y,Z[,INTENSITY] (intensity at distance 1)")
      ->delimiter(',')
      ->expected(3, 4)
      ->allow_extra_args(false);
  command->add_option("--size", options->size, "Frame size WIDTHxHEIGHT")->capture_default_str();
  command
      ->add_option(
          "--texture-size", options->texture_size,
          "Texels per side of the synthesized subspace images (default: the frame's densest visible texels, "
          "a power of two up to 1024)")
      ->check(CLI::Range(16u, 8192u));
  command->add_flag(
      "!--no-prune", options->prune,
      "Synthesize every subspace image, not only those the frame's (light, view) pairs fall in");
  command->add_flag("--measure-savings", options->measure_savings,
                    "Also time the synthesis of every subspace image, to report what pruning saved");
  command->add_option("--seed", options->seed, "Synthesis and range-map layout seed")
      ->check(non_negative())
      ->capture_default_str();
  add_parallax_options(*command, options->parallax, options->parallax_steps);
  command->add_flag("--hand-filtering", options->hand_filtering,
                    "Filter the subspace images by hand, as the CPU reference does, instead of through the "
                    "sampler's trilinear filtering (slower; the default where the device filters RGBA32F)");
  add_direction_taps_option(*command, options->pair_coupling);
  command->add_option("--out", options->out, "Output image: .png (sRGB) or .exr (linear)")
      ->capture_default_str();
  command->add_option(
      "--compare", options->compare,
      "A measured BTF (the one the material came from): also render its images, interpolated the same "
      "way, on the same mesh, view and lights; writes OUT_measured and OUT_compare (model | measured)");
  add_device_options(*command, options->device);
  command->callback([options] { run_render(*options); });
}

}  // namespace carbtf::cli
