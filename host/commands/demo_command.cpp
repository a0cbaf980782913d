// `carbtf demo`: the README's main job, the whole pipeline on built-in data. A sample material is
// rendered as a UBO2003 BTF (81 x 81 images), analysed into a material file, synthesized on the Vulkan
// device (checked bit for bit against the CPU reference), scored for fidelity beside the measurement
// through the same render pass, and rendered on a sphere. A report folder holds the pictures, the figures and
// an index.html.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <thread>
#include <vector>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/sample/sample_btf.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "fidelity/fidelity_run.hpp"
#include "report/analysis_report.hpp"
#include "report/demo_report.hpp"
#include "report/pictures.hpp"
#include "scene/material_render.hpp"
#include "scene/orbit.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  DeviceOptions device;
  std::string out = "carbtf-demo";
  std::string material = "leather";
  // Sample images, texels per side. At 128 the demo took 36 s, but its leather scored a mean rel of
  // 0.53 and its cells hardly showed in the fidelity grid; at 256 it takes about 100 s and scores 0.35
  // (seed 7, 2 cores, lavapipe): the first picture a user sees should look like the material.
  std::uint32_t size = 256;
  // Synthesized subspace images, texels per side: 512 puts four 128-texel range tiles round the
  // sphere. With 256 there were two, and two tiles built from the same four patches share much of
  // them: the relief half way round matched the front's (heights differing by RMS 0.81 against 1.63
  // for unrelated texels, seed 7), and the sphere's back looked like its front.
  std::uint32_t texture_size = 512;
  std::uint64_t seed = 7;
};

void step(int index, const char* text) {
  std::printf("[%d/6] %s\n", index, text);
  std::fflush(stdout);
}

void run_demo(const DemoOptions& options) {
  const fs::path folder = fs::absolute(options.out);
  create_folder(folder);
  DemoFigures figures;
  figures.material = options.material;
  figures.sample_size = options.size;
  figures.texture_size = options.texture_size;
  auto timed = [&figures](const std::string& name, double seconds) {
    figures.stage_times.push_back({name, seconds});
  };

  // 1. A measured BTF to start from.
  const std::string sample = std::to_string(options.size);
  step(1, ("sample material '" + options.material + "': 81 x 81 images of " + sample + "^2").c_str());
  auto start = std::chrono::steady_clock::now();
  const Surface surface = make_sample_surface(options.material, options.size, options.seed);
  const fs::path btf_folder = folder / "btf";
  write_sample_btf(surface, btf_folder, ".png", false);
  timed("sample BTF rendering (81 x 81 images)", seconds_since(start));

  // 2. Analysis into a material file.
  step(2, "analysis: segmentation, photometric stereo, range tiles, colour PCA, pyramid, CAR fits");
  start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(btf_folder, {}, warnings);
  timed("BTF loading", seconds_since(start));
  AnalysisOptions analysis;
  analysis.progress = false;
  const AnalysisResult result = analyze_btf(dataset, analysis);
  for (const StageReport& s : result.stages) timed("analysis: " + s.name, s.seconds);
  const fs::path material_path = folder / (options.material + ".cbtf");
  check(write_material_file(material_path, result.material), "cannot write the material");
  write_analysis_report(folder / "analysis", dataset, result);
  const Material& material = result.material;
  const double raw_bytes = figures.raw_bytes =
      static_cast<double>(dataset.present_pairs().size()) * static_cast<double>(dataset.pixel_count()) * 3.0;
  const double file_bytes = figures.file_bytes = static_cast<double>(fs::file_size(material_path));

  // 3. Synthesis on the device, and its CPU twin.
  auto context = make_context(options.device);
  const std::uint32_t n = options.texture_size;
  step(3, ("synthesis of " + std::to_string(material.subspaces.size()) + " subspace images of " +
           std::to_string(n) + "^2 on " + context->device_info().name + ", and the CPU reference")
              .c_str());
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
  SynthesisRequest request;
  request.seed = options.seed;
  request.width = request.height = n;
  request.periodic_overlap = default_periodic_overlap(n, n);  // step 5 wraps them round a sphere
  request.mip_levels = 0;                                     // and samples every level
  SynthesizedImages images;
  SynthesisTiming timing;
  start = std::chrono::steady_clock::now();
  check(synthesizer->synthesize(material, request, images, &timing), "synthesis failed");
  timed("GPU synthesis, all subspace images (wall, with readback)", seconds_since(start));
  start = std::chrono::steady_clock::now();
  const SynthesisBlock& block = request;
  const std::vector<std::vector<float>> cpu = reference::synthesize_subspaces(material, {}, block);
  timed("CPU reference synthesis (" + std::to_string(std::thread::hardware_concurrency()) + " threads)",
        seconds_since(start));
  std::size_t texels = 0;
  const std::size_t differing = differing_values(cpu, images.images, texels);
  for (std::size_t s = 0; s < images.images.size(); ++s) {
    write_rgb_image(folder / ("synthesized_" + two_digits(s) + ".png"),
                    channels_to_rgb(images.images[s], images.channels[s], std::size_t{n} * n), n, n);
  }

  // 4. Fidelity: the model and the measurement through the same render pass at a spread of measured
  // (light, view) pairs, scored by the calibrated texture measure.
  step(4, "fidelity: model and measurement through the same render pass, grazing light included");
  start = std::chrono::steady_clock::now();
  FidelityRunOptions fidelity_options;
  fidelity_options.seed = options.seed;
  const std::vector<PairFidelity> fidelity =
      run_fidelity(*context, material, dataset, default_fidelity_pairs(material), fidelity_options);
  const FidelitySummaryLine fidelity_summary = summarize(fidelity);
  const RgbField grid = fidelity_grid(fidelity);
  write_rgb_image(folder / "fidelity_grid.png", grid.rgb, grid.width, grid.height);
  write_output_file(folder / "fidelity.csv", fidelity_csv(fidelity, material));
  timed(
      "fidelity (" + std::to_string(fidelity.size()) + " pairs: synthesis, two renders and the measure each)",
      seconds_since(start));
  // 5. The material on a sphere, from the front and from behind, where u wraps (the images are periodic).
  step(5, "render on a sphere, 960x640, front and back");
  const MaterialRender sphere_render = prepare_material_render(*context, material, *synthesizer, options.seed,
                                                               1.0f, 960, 640, make_sphere(), true);
  for (const float side : {0.0f, 180.0f}) {
    const RenderScene scene = demo_sphere_scene(side);
    RenderedImage sphere;
    start = std::chrono::steady_clock::now();
    check(sphere_render.renderer->render(scene, sphere), "rendering the sphere failed");
    timed("render, sphere 960x640 (wall)", seconds_since(start));
    write_rgb_image(folder / (side == 0 ? "sphere.png" : "sphere_back.png"), rendered_rgb(sphere), 960, 640);
  }
  check_validation(*context);

  // 6. The report.
  step(6, "report");
  figures.subspaces = material.subspaces.size();
  figures.measured_images = dataset.present_pairs().size();
  figures.device = context->device_info().name + " (" + device_type_name(context->device_info().type) + ")";
  figures.identical_values = texels - differing;
  figures.values = texels;
  figures.gpu_synthesis_ms = timing.total_ms;
  write_demo_report(folder, figures, fidelity);

  std::printf(
      "material %.1f KiB, ratio 1 : %.0f; GPU synthesis %.1f ms, bit-identical to the CPU on %zu of "
      "%zu values\n",
      file_bytes / 1024.0, raw_bytes / file_bytes, timing.total_ms, texels - differing, texels);
  std::printf("fidelity: %s\n", summary_text(fidelity_summary).c_str());
  std::printf("report: %s\n", (folder / "index.html").c_str());
  if (differing != 0) throw CommandError("the GPU synthesis differs from the CPU reference");
}

}  // namespace

void register_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  auto* command = app.add_subcommand("demo",
                                     "Run the whole pipeline on built-in data (sample BTF, analysis, GPU "
                                     "synthesis, render) and write an HTML report");
  command->add_option("--out", options->out, "Report folder")->capture_default_str();
  command
      ->add_option("--material", options->material, "Built-in sample material (see `carbtf sample --help`)")
      ->capture_default_str();
  command
      ->add_option("--size", options->size,
                   "Sample images: texels per side (smaller runs faster but models the material less "
                   "closely: 128 takes about a third of the time)")
      ->check(CLI::Range(32u, 512u))
      ->capture_default_str();
  command->add_option("--texture-size", options->texture_size, "Synthesized subspace images: texels per side")
      ->check(CLI::Range(32u, 2048u))
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed of the sample, the analysis and the synthesis")
      ->check(non_negative())
      ->capture_default_str();
  add_device_options(*command, options->device);
  command->callback([options] { run_demo(*options); });
}

}  // namespace carbtf::cli
