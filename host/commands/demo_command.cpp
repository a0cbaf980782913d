// `carbtf demo`: the README's main job, the whole pipeline on built-in data. A sample material is
// rendered as a UBO2003 BTF (81 x 81 images), analysed into a material file, synthesized on the Vulkan
// device (checked bit for bit against the CPU reference) and rendered on a plane beside the
// measurement and on a sphere. A report folder holds the pictures, the figures and an index.html.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <thread>
#include <vector>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/quality/fidelity.hpp"
#include "carbtf/analysis/reference/subspace_synthesis.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material_binding.hpp"
#include "carbtf/engine/material_file.hpp"
#include "carbtf/engine/mesh_renderer.hpp"
#include "carbtf/engine/subspace_synthesizer.hpp"
#include "cli/cli_support.hpp"
#include "cli/sample_btf.hpp"
#include "commands/commands.hpp"
#include "report/analysis_report.hpp"
#include "report/html_report.hpp"
#include "report/pictures.hpp"
#include "scene/orbit.hpp"

namespace carbtf::cli {

namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  DeviceOptions device;
  std::string out = "carbtf-demo";
  std::string material = "leather";
  std::uint32_t size = 128;          // sample images, texels per side
  std::uint32_t texture_size = 256;  // synthesized subspace images
  std::uint64_t seed = 7;
};

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

void step(int index, const char* text) {
  std::printf("[%d/6] %s\n", index, text);
  std::fflush(stdout);
}

struct Comparison {
  std::string name;
  std::uint32_t light = 0;  // UBO2003 indices
  std::uint32_t view = 0;
  FidelityError error;
};

void run_demo(const DemoOptions& options) {
  const fs::path folder = fs::absolute(options.out);
  create_folder(folder);
  std::vector<std::vector<std::string>> times{{"stage", "time"}};
  auto timed = [&times](const std::string& name, double seconds) {
    times.push_back({name, format("%.2f s", seconds)});
  };

  // 1. A measured BTF to start from.
  step(1, ("sample material '" + options.material + "': 81 x 81 images of " + std::to_string(options.size) +
           "^2")
              .c_str());
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
  const double raw_bytes =
      static_cast<double>(dataset.present_pairs().size()) * static_cast<double>(dataset.pixel_count()) * 3.0;
  const auto file_bytes = static_cast<double>(fs::file_size(material_path));

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
  std::size_t texels = 0, differing = 0;
  for (std::size_t s = 0; s < cpu.size(); ++s) {
    texels += cpu[s].size();
    for (std::size_t i = 0; i < cpu[s].size(); ++i)
      differing += std::memcmp(&cpu[s][i], &images.images[s][i], sizeof(float)) != 0;
  }
  for (std::size_t s = 0; s < images.images.size(); ++s) {
    write_rgb_image(folder / ("synthesized_" + two_digits(s) + ".png"),
                    channels_to_rgb(images.images[s], images.channels[s], std::size_t{n} * n), n, n);
  }

  // 4. The render pass on a plane, beside the measurement, at measured (light, view) pairs.
  step(4, "render on a plane beside the measured images");
  MaterialBindingInfo binding_info;
  binding_info.seed = options.seed;
  std::unique_ptr<MaterialBinding> binding;
  check(MaterialBinding::create(*context, material, material_textures(*synthesizer, material), binding_info,
                                binding),
        "cannot bind the material");
  check(binding->upload_and_wait(), "cannot upload the range map");
  // One texel per pixel over as many texels as the rectified measurement shows, so that model and
  // measurement have the same scale and sampling for the fidelity figures.
  const std::uint32_t plane_size = std::min(options.size, n);
  RenderTargetInfo plane_target;
  plane_target.width = plane_target.height = plane_size;
  plane_target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
  std::unique_ptr<MeshRenderer> plane_renderer;
  check(MeshRenderer::create(*context, *binding, plane_target, plane_renderer),
        "cannot build the render pass");
  check(plane_renderer->set_mesh(make_plane()), "cannot upload the plane");
  std::vector<Comparison> comparisons = {
      {"light 45 deg", *ubo2003_index(45, 0), *ubo2003_index(0, 0), {}},
      {"grazing light 75 deg", *ubo2003_index(75, 90), *ubo2003_index(0, 0), {}}};
  std::vector<float> measured(dataset.pixel_count() * 3);
  double plane_ms = 0.0;
  for (Comparison& c : comparisons) {
    RenderScene scene;
    // Straight down, orthographic; the 2 x 2 plane holds n texels.
    scene.camera.eye = {0, 0, 3};
    scene.camera.up = {0, 1, 0};
    scene.camera.fov_y_degrees = 0.0f;
    scene.camera.ortho_height = 2.0f * static_cast<float>(plane_size) / static_cast<float>(n);
    scene.lights = {{false,
                     unit_vector_degrees(dataset.lights()[c.light].theta_degrees(),
                                         dataset.lights()[c.light].phi_degrees()),
                     {1, 1, 1}}};
    RenderedImage frame;
    start = std::chrono::steady_clock::now();
    check(plane_renderer->render(scene, frame), "rendering the plane failed");
    plane_ms += seconds_since(start) * 1e3;
    const std::vector<float> model = rendered_rgb(frame);
    dataset.linear_rgb({c.light, c.view}, measured);
    c.error = fidelity_error(model, plane_size, plane_size, measured, dataset.width(), dataset.height());
    const std::string stem = "plane_l" + std::to_string(c.light) + "_v" + std::to_string(c.view);
    write_rgb_image(folder / (stem + "_model.png"), model, plane_size, plane_size);
    write_rgb_image(folder / (stem + "_measured.png"), measured, dataset.width(), dataset.height());
  }
  timed("render, plane " + std::to_string(plane_size) + "^2 (mean of " + std::to_string(comparisons.size()) +
            ", wall)",
        plane_ms / 1e3 / static_cast<double>(comparisons.size()));

  // 5. The material on a sphere.
  step(5, "render on a sphere, 960x640");
  RenderTargetInfo sphere_target;
  sphere_target.width = 960;
  sphere_target.height = 640;
  sphere_target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
  std::unique_ptr<MeshRenderer> sphere_renderer;
  check(MeshRenderer::create(*context, *binding, sphere_target, sphere_renderer),
        "cannot build the render pass");
  check(sphere_renderer->set_mesh(make_sphere()), "cannot upload the sphere");
  RenderScene sphere_scene;
  sphere_scene.camera.eye = {2.6f, 1.8f, 1.5f};
  sphere_scene.lights = {{false, unit_vector_degrees(50, 80), {1, 1, 1}},
                         {false, unit_vector_degrees(70, 250), {0.25f, 0.25f, 0.3f}}};
  RenderedImage sphere;
  start = std::chrono::steady_clock::now();
  check(sphere_renderer->render(sphere_scene, sphere), "rendering the sphere failed");
  timed("render, sphere 960x640 (wall)", seconds_since(start));
  write_rgb_image(folder / "sphere.png", rendered_rgb(sphere), sphere.width, sphere.height);
  check_validation(*context);

  // 6. The report.
  step(6, "report");
  HtmlReport report("carbtf demo: " + options.material);
  report.paragraph(
      "The whole pipeline on built-in data: a sample material rendered as a measured BTF (81 lights x 81 "
      "views), analysed into a material file of a few tens of kilobytes, synthesized on the Vulkan device "
      "at any size, and rendered with parallax bump mapping.");
  report.heading("The material on a sphere");
  report.image("sphere.png", "model, " + std::to_string(n) + "^2 synthesized texture, two directional lights",
               960);
  report.heading("Model beside measurement");
  report.paragraph(
      "A plane seen straight down, lit from a measured direction, beside the measured image of that "
      "(light, view) pair. The model is a random field: it matches statistics, not pixels, so the "
      "fidelity figures (DESIGN.md 5) say how close it is.");
  std::vector<std::vector<std::string>> fidelity{
      {"pair", "delta E (Lab)", "std rel. error", "spectrum L1", "histogram W1"}};
  for (const Comparison& c : comparisons) {
    const std::string stem = "plane_l" + std::to_string(c.light) + "_v" + std::to_string(c.view);
    report.image_row(
        {{stem + "_model.png", "model, " + c.name}, {stem + "_measured.png", "measured, " + c.name}});
    fidelity.push_back({c.name, format("%.2f", c.error.delta_e), format("%.3f", c.error.std_relative),
                        format("%.3f", c.error.spectrum_l1), format("%.2f", c.error.histogram_w1)});
  }
  report.table(fidelity);
  report.heading("Analysis");
  report.image_row({{"analysis/index_table.png", "subspace index table (lights x views)"},
                    {"analysis/eigenvalues.png", "eigenvalue spectrum of the segmentation features"}},
                   420);
  std::vector<std::pair<std::string, std::string>> subspaces;
  for (std::size_t s = 0; s < std::min<std::size_t>(images.images.size(), 6); ++s) {
    subspaces.push_back(
        {"analysis/subspace_" + two_digits(s) + ".png", "subspace " + std::to_string(s) + ", measured"});
    subspaces.push_back(
        {"synthesized_" + two_digits(s) + ".png", "subspace " + std::to_string(s) + ", synthesized"});
  }
  report.heading("Subspace images, measured and synthesized");
  report.image_row(subspaces, 160);
  report.heading("Figures");
  report.table(
      {{"figure", "value"},
       {"device", context->device_info().name + " (" + device_type_name(context->device_info().type) + ")"},
       {"measured BTF", std::to_string(dataset.present_pairs().size()) + " images of " +
                            std::to_string(options.size) + "^2, " +
                            format("%.1f MiB as 8-bit RGB", raw_bytes / 1048576.0)},
       {"material file", format("%.1f KiB", file_bytes / 1024.0) + ", " +
                             std::to_string(material.subspaces.size()) + " subspaces"},
       {"compression ratio", "1 : " + format("%.0f", raw_bytes / file_bytes)},
       {"GPU vs CPU synthesis",
        std::to_string(texels - differing) + " of " + std::to_string(texels) + " values bit-identical"},
       {"GPU synthesis time (timestamps)", format("%.1f ms", timing.total_ms)}});
  report.table(times);
  if (std::string error; !report.write(folder, error)) throw CommandError(error);

  std::printf(
      "material %.1f KiB, ratio 1 : %.0f; GPU synthesis %.1f ms, bit-identical to the CPU on %zu of %zu "
      "values\n",
      file_bytes / 1024.0, raw_bytes / file_bytes, timing.total_ms, texels - differing, texels);
  for (const Comparison& c : comparisons) {
    std::printf("model vs measured, %s: delta E %.2f, spectrum L1 %.3f\n", c.name.c_str(), c.error.delta_e,
                c.error.spectrum_l1);
  }
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
  command->add_option("--size", options->size, "Sample images: texels per side")
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
