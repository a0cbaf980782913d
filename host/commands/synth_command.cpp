// `carbtf synth material.cbtf --size N --out DIR`: subspace images of a material at any size, on the
// Vulkan device or the CPU reference, and the interpolated image of one (light, view).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "report/pictures.hpp"
#include "scene/direction_query.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct SynthOptions {
  DeviceOptions device;
  std::string material;
  std::string out = "synth";
  std::uint32_t size = 512;
  std::uint32_t width = 0;  // 0: --size
  std::uint32_t height = 0;
  std::int32_t row0 = 0;
  std::int32_t col0 = 0;
  std::uint64_t seed = 1;
  std::uint32_t margin = 64;
  std::vector<std::uint32_t> subspaces;
  std::vector<double> light;  // theta, phi in degrees
  std::vector<double> view;
  CarScheme scheme = CarScheme::automatic;
  bool float64 = false;
  bool periodic = false;
};

void run_synth(const SynthOptions& options) {
  Material material;
  check(read_material_file(options.material, material), "cannot read the material");
  if (options.light.empty() != options.view.empty()) throw CommandError("--light and --view go together");

  SynthesisRequest request;
  request.seed = options.seed;
  request.width = options.width ? options.width : options.size;
  request.height = options.height ? options.height : options.size;
  request.row0 = options.row0;
  request.col0 = options.col0;
  request.margin = options.margin;
  if (options.periodic) request.periodic_overlap = default_periodic_overlap(request.width, request.height);
  request.subspaces = options.subspaces;
  request.scheme = options.scheme;
  require_subspaces(material, request.subspaces, options.material);
  Interpolation interpolation;
  if (!options.light.empty()) {
    interpolation = interpolation_of(material, options.light, options.view);
    request.subspaces = subspaces_with(request.subspaces, interpolation);
  }
  std::vector<std::uint32_t> listed = request.subspaces;
  if (listed.empty()) {
    for (std::uint32_t s = 0; s < material.subspaces.size(); ++s) listed.push_back(s);
  }
  const fs::path out = options.out;
  create_folder(out);

  const bool on_cpu = options.device.device == "cpu";
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::vector<float>> images;
  std::vector<float> interpolated;
  std::string where;
  double gpu_ms = 0.0;
  if (on_cpu) {
    std::printf("synthesizing %zu subspace images of %ux%u on the CPU reference (%s)...\n", listed.size(),
                request.width, request.height, options.float64 ? "float64" : "float32");
    std::fflush(stdout);
    if (options.float64) {
      const auto f64 = reference::synthesize_subspaces_f64(material, listed, request);
      images.resize(f64.size());
      for (std::size_t s = 0; s < f64.size(); ++s) images[s].assign(f64[s].begin(), f64[s].end());
    } else {
      images = reference::synthesize_subspaces(material, listed, request);
    }
    if (!interpolation.subspaces.empty()) {
      interpolated.resize(std::size_t{request.width} * request.height *
                          material.subspaces[interpolation.subspaces[0]].channels);
      reference::interpolate_subspaces(material, interpolation.weights, images, interpolated);
    }
    where = "the CPU reference";
  } else {
    if (options.float64) throw CommandError("--float64 needs --device cpu (the GPU synthesizes in float32)");
    auto context = make_context(options.device);
    std::unique_ptr<SubspaceSynthesizer> synthesizer;
    check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
    SynthesizedImages result;
    SynthesisTiming timing;
    check(synthesizer->synthesize(material, request, result, &timing), "synthesis failed");
    images = std::move(result.images);
    gpu_ms = timing.total_ms;
    if (!interpolation.subspaces.empty()) {
      check(synthesizer->interpolate(material, interpolation.weights, interpolated), "interpolation failed");
    }
    check_validation(*context);
    where = context->device_info().name + " (" + car_scheme_name(synthesizer->scheme()) + " CAR scheme)";
  }
  const double seconds = seconds_since(start);
  for (std::uint32_t s : listed)
    require_finite(images[s], options.material + ": synthesized subspace image " + std::to_string(s));
  require_finite(interpolated, options.material + ": interpolated image");

  for (std::uint32_t s : listed)
    write_png_and_exr(out, "subspace_" + two_digits(s), images[s], material.subspaces[s].channels,
                      request.width, request.height);
  std::printf(
      "synthesized %zu of %zu subspace images, %ux%u each (%.1f Mtexels), seed %llu, on %s in %.1f ms%s\n",
      listed.size(), material.subspaces.size(), request.width, request.height,
      static_cast<double>(listed.size()) * request.width * request.height * 1e-6,
      static_cast<unsigned long long>(request.seed), where.c_str(), seconds * 1e3,
      gpu_ms > 0 ? (" (GPU time " + std::to_string(static_cast<int>(std::lround(gpu_ms))) + " ms)").c_str()
                 : "");
  std::printf("wrote %s/subspace_NN.png (sRGB) and .exr (linear)\n", out.string().c_str());
  if (!interpolated.empty()) {
    write_png_and_exr(out, "interpolated", interpolated,
                      material.subspaces[interpolation.subspaces[0]].channels, request.width, request.height);
    std::printf("wrote %s/interpolated.png and .exr: light (%g, %g) deg, view (%g, %g) deg, weights:%s\n",
                out.string().c_str(), options.light[0], options.light[1], options.view[0], options.view[1],
                describe_weights(interpolation.weights).c_str());
  }
}

}  // namespace

void register_synth_command(CLI::App& app) {
  auto options = std::make_shared<SynthOptions>();
  auto* command = app.add_subcommand(
      "synth",
      "Synthesize subspace images of a material at any size (PNG sRGB and EXR linear), and the image of one "
      "(light, view) by 9-weight interpolation");
  command->add_option("material", options->material, "Material file (.cbtf) from `carbtf analyze`")
      ->required();
  command->add_option("--out", options->out, "Output folder")->capture_default_str();
  command->add_option("--size", options->size, "Width and height in texels")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command->add_option("--width", options->width, "Width, overriding --size")->check(CLI::Range(1u, 16384u));
  command->add_option("--height", options->height, "Height, overriding --size")
      ->check(CLI::Range(1u, 16384u));
  command
      ->add_option("--row0", options->row0,
                   "First row of the block of the unbounded texture (noise is addressed by absolute "
                   "position, so blocks of one seed continue each other once the burn-in has decayed)")
      ->capture_default_str();
  command->add_option("--col0", options->col0, "First column of the block")->capture_default_str();
  command
      ->add_option("--seed", options->seed, "Seed (64-bit): same seed, same images, on the CPU and the GPU")
      ->check(non_negative())
      ->capture_default_str();
  command
      ->add_option("--margin", options->margin,
                   "The most CAR burn-in rows and columns a band gets (each takes what its stability needs, "
                   "docs/design.md 4.4)")
      ->check(CLI::Range(0u, 4096u))
      ->capture_default_str();
  command
      ->add_option(
          "--subspaces", options->subspaces,
          "Comma-separated subspace indices to synthesize (default: all, or with --light/--view only those "
          "the interpolated image needs)")
      ->delimiter(',')
      ->check(non_negative());
  command
      ->add_option("--light", options->light,
                   "Light direction THETA,PHI in degrees: also write the interpolated image")
      ->delimiter(',')
      ->expected(2)
      ->check(CLI::Range(-360.0, 360.0));
  command->add_option("--view", options->view, "View direction THETA,PHI in degrees (with --light)")
      ->delimiter(',')
      ->expected(2)
      ->check(CLI::Range(-360.0, 360.0));
  command->add_flag(
      "--periodic", options->periodic,
      "Tileable images (closed meshes, repeated textures): the last "
      "eighth of each side (4 to 64 texels) folds onto the first, keeping the texture's statistics");
  add_car_scheme_option(*command, options->scheme);
  command->add_flag("--float64", options->float64,
                    "With --device cpu: the float64 reference (the accuracy reference)");
  command->add_option(
      "--device", options->device.device,
      "cpu: the CPU reference; gpu: the best Vulkan device; else a Vulkan device index or part of its name, "
      "as `carbtf devices` lists them (default: $CARBTF_DEVICE, else the best device)");
  command->add_flag("--validation", options->device.validation,
                    "Enable the Vulkan validation layer; any message it reports fails the command");
  command->callback([options] { run_synth(*options); });
}

}  // namespace carbtf::cli
