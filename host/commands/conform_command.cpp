// `carbtf conform [material.cbtf]`: headless GPU-vs-CPU conformance of subspace synthesis. Runs the
// Vulkan pipeline and the CPU float32 reference on the same material, seed and size, compares every
// stage pixel by pixel, checks block-wise synthesis against the whole, reports float32 against float64,
// and exits non-zero beyond the tolerance.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <thread>

#include "carbtf/analysis/reference/conformance.hpp"
#include "carbtf/analysis/reference/noise.hpp"
#include "carbtf/analysis/reference/subspace_synthesis.hpp"
#include "carbtf/analysis/sample/synthetic_material.hpp"
#include "carbtf/engine/direction_interpolation.hpp"
#include "carbtf/engine/material_file.hpp"
#include "carbtf/engine/subspace_synthesizer.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {
namespace {

using reference::ConformanceError;

struct ConformOptions {
  DeviceOptions device;
  std::string material;
  std::uint32_t size = 512;
  std::uint64_t seed = 1;
  std::uint32_t margin = 64;
  double tolerance = 1e-5;
  bool extremes = true;
  std::uint32_t large_size = 4096;
  std::vector<std::uint32_t> growth_sizes = {256, 512, 1024, 2048, 4096};
  CarScheme scheme = CarScheme::automatic;
};

struct StageResult {
  explicit StageResult(std::string name) : stage(std::move(name)) {}
  std::string stage;
  std::uint32_t items = 0;
  ConformanceError error;
  bool identical = true;
};

struct CaseReport {
  std::string name;
  std::vector<StageResult> stages;
  double gpu_ms = 0.0;
  double cpu_ms = 0.0;
  ConformanceError float32_vs_float64;
};

bool bitwise_equal(std::span<const float> a, std::span<const float> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

void accumulate(StageResult& stage, std::span<const float> gpu, std::span<const float> cpu,
                std::uint32_t channels) {
  stage.error = reference::worst_of(stage.error, reference::conformance_error(gpu, cpu, channels));
  stage.identical = stage.identical && bitwise_equal(gpu, cpu);
  ++stage.items;
}

// Interpolation queries: a measured pair, a point between measured directions, and grazing angles
// beyond the last measured elevation.
std::vector<std::array<double, 4>> interpolation_queries(const Material& m) {
  constexpr double d = std::numbers::pi / 180.0;
  return {{m.lights[0].theta, m.lights[0].phi, m.views[m.views.size() - 1].theta,
           m.views[m.views.size() - 1].phi},
          {37.0 * d, 101.0 * d, 52.0 * d, 203.0 * d},
          {89.0 * d, 10.0 * d, 87.0 * d, 190.0 * d}};
}

// Block-wise synthesis: the output as a 2 x 2 grid of blocks, each synthesized on its own (margin 0)
// from block initialization values of `whole`, against the same region of the whole GPU images.
StageResult blockwise_stage(const Material& material, const SynthesisRequest& whole,
                            const SynthesizedImages& images, SubspaceSynthesizer& synthesizer) {
  StageResult stage("block-wise");
  std::vector<SynthesisBlock> blocks;
  const std::uint32_t half_rows = std::max(1u, whole.height / 2), half_cols = std::max(1u, whole.width / 2);
  for (std::uint32_t r = 0; r < whole.height; r += half_rows) {
    for (std::uint32_t c = 0; c < whole.width; c += half_cols) {
      SynthesisBlock block = whole;
      block.row0 = whole.row0 + static_cast<std::int32_t>(r);
      block.col0 = whole.col0 + static_cast<std::int32_t>(c);
      block.height = std::min(half_rows, whole.height - r);
      block.width = std::min(half_cols, whole.width - c);
      block.margin = 0;
      blocks.push_back(block);
    }
  }
  const auto initial = reference::block_initial_values(material, {}, whole, blocks);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    SynthesisRequest request;
    static_cast<SynthesisBlock&>(request) = blocks[b];
    request.scheme = whole.scheme;
    request.poison = true;
    request.initial_values = initial[b];
    SynthesizedImages tile;
    check(synthesizer.synthesize(material, request, tile), "block-wise GPU synthesis failed");
    for (std::size_t s = 0; s < material.subspaces.size(); ++s) {
      const std::uint32_t channels = material.subspaces[s].channels;
      std::vector<float> expected;
      for (std::uint32_t r = 0; r < request.height; ++r) {
        const std::size_t first =
            (std::size_t{static_cast<std::uint32_t>(request.row0 - whole.row0) + r} * whole.width +
             static_cast<std::uint32_t>(request.col0 - whole.col0)) *
            channels;
        expected.insert(expected.end(), images.images[s].begin() + static_cast<std::ptrdiff_t>(first),
                        images.images[s].begin() +
                            static_cast<std::ptrdiff_t>(first + std::size_t{request.width} * channels));
      }
      accumulate(stage, tile.images[s], expected, channels);
    }
  }
  return stage;
}

CaseReport run_case(const std::string& name, const Material& material, std::uint32_t size,
                    const ConformOptions& options, SubspaceSynthesizer& synthesizer) {
  CaseReport report;
  report.name = name;
  SynthesisRequest request;
  request.seed = options.seed;
  request.width = request.height = size;
  request.margin = options.margin;
  request.poison = true;
  request.scheme = options.scheme;
  const std::size_t count = material.subspaces.size();

  // CPU float32 stages: the bands, which become the collapsed levels once compared and are then freed.
  // The GPU's captures stay on the device (run(), no image read back) and the CPU images are computed
  // again for the colour check, after the stages are gone; the float64 reference comes last, a few
  // subspaces at a time, after the whole-size GPU buffers are gone. One image-sized copy of each kind
  // at a time bounds a 4096^2 case's memory (issue 14).
  const SynthesisBlock& block = request;
  std::vector<reference::SubspaceStages> stages(count);
  std::vector<std::vector<float>> cpu(count);
  auto start = std::chrono::steady_clock::now();
  for (std::size_t s = 0; s < count; ++s) {
    cpu[s].resize(std::size_t{size} * size * material.subspaces[s].channels);
    reference::synthesize_subspace(material, static_cast<std::uint32_t>(s), block, cpu[s], &stages[s]);
    std::vector<float>().swap(cpu[s]);
  }
  report.cpu_ms = seconds_since(start) * 1e3;

  StageResult noise("noise"), band("band fields"), collapse("collapse"), colour("colour"),
      interpolation("interpolation");
  SynthesizedImages images;
  for (SynthesisStage capture : {SynthesisStage::noise, SynthesisStage::car, SynthesisStage::collapse}) {
    request.capture = capture;
    check(synthesizer.run(material, request), name + ": GPU synthesis failed");
    for (std::uint32_t s = 0; s < count; ++s) {
      const SubspaceModel& model = material.subspaces[s];
      for (std::uint32_t level = 0; level < model.levels; ++level) {
        for (std::uint32_t c = 0; c < model.channels; ++c) {
          std::vector<float> gpu;
          std::uint32_t rows = 0, cols = 0;
          check(synthesizer.read_band(s, level, c, gpu, rows, cols), name + ": reading a band");
          const std::size_t index = std::size_t{level} * model.channels + c;
          if (capture == SynthesisStage::noise) {
            const TextureRegion& region = stages[s].regions[level];
            std::vector<float> expected(gpu.size());
            reference::fill_noise_block(request.seed, field_id_of(s, level, c),
                                        static_cast<std::int32_t>(region.row0),
                                        static_cast<std::int32_t>(region.col0), cols, rows, expected, 1);
            accumulate(noise, gpu, expected, 1);
          } else if (capture == SynthesisStage::car) {
            const float mean = model.bands[index].mean;
            for (float& v : gpu) v = mean + v;  // the reference's band is mean + y, one float add
            accumulate(band, gpu, stages[s].band[index], 1);
          } else {
            accumulate(collapse, gpu, stages[s].band[index], 1);  // G since the car pass
            std::vector<float>().swap(stages[s].band[index]);
          }
        }
      }
      if (capture == SynthesisStage::car) reference::collapse_band_stages(stages[s]);
    }
  }
  stages = {};
  request.capture = SynthesisStage::none;
  SynthesisTiming timing;
  check(synthesizer.synthesize(material, request, images, &timing), name + ": GPU synthesis failed");
  report.gpu_ms = timing.total_ms;
  for (std::size_t s = 0; s < count; ++s) {
    cpu[s].resize(std::size_t{size} * size * material.subspaces[s].channels);
    reference::synthesize_subspace(material, static_cast<std::uint32_t>(s), block, cpu[s]);
    accumulate(colour, images.images[s], cpu[s], material.subspaces[s].channels);
    std::vector<float>().swap(cpu[s]);
  }
  DirectionTriangulation lights, views;
  check(build_direction_triangulation(material.lights, lights), name + ": light directions");
  check(build_direction_triangulation(material.views, views), name + ": view directions");
  for (const auto& [lt, lp, vt, vp] : interpolation_queries(material)) {
    const PairWeights weights = pair_weights(lights, views, lt, lp, vt, vp);
    std::vector<float> gpu;
    check(synthesizer.interpolate(material, weights, gpu), name + ": GPU interpolation failed");
    std::vector<float> expected(gpu.size());
    // The stage alone: both sides interpolate the GPU's subspace images (the colour stage compared them).
    reference::interpolate_subspaces(material, weights, images.images, expected);
    accumulate(interpolation, gpu, expected, material.subspaces[0].channels);
  }
  synthesizer.release();  // the blocks allocate their own, smaller buffers
  const StageResult blockwise = blockwise_stage(material, request, images, synthesizer);
  // float64 last, a few subspaces at a time, once the whole-size GPU buffers are gone.
  const unsigned batch = std::max(1u, std::thread::hardware_concurrency());
  for (std::size_t first = 0; first < count; first += batch) {
    std::vector<std::uint32_t> list;
    for (std::size_t s = first; s < std::min<std::size_t>(count, first + batch); ++s)
      list.push_back(static_cast<std::uint32_t>(s));
    const auto f64 = reference::synthesize_subspaces_f64(material, list, block);
    for (const std::uint32_t s : list) {
      report.float32_vs_float64 = reference::worst_of(
          report.float32_vs_float64,
          reference::conformance_error(images.images[s], f64[s], material.subspaces[s].channels));
    }
  }
  report.stages = {noise, band, collapse, colour, interpolation, blockwise};
  return report;
}

// A near-unit-root band: separable (1 - 0.99 z1)(1 - 0.99 z2), spectral radius 0.99, the largest the
// analysis keeps after repair.
Material near_unit_root_material() {
  Material m = synthetic_material(1, 1);
  for (CarBandModel& b : m.subspaces[0].bands) {
    b.neighbourhood = {{0, -1}, {-1, 0}, {-1, -1}};
    b.gamma = {0.99f, 0.99f, -0.9801f};
    b.sigma = 1.0f;
  }
  return m;
}

// The largest neighbourhoods: 12 neighbours (the analysis's widest) and 16 (the GPU's limit).
Material largest_neighbourhood_material() {
  Material m = synthetic_material(2, 3, 3, 12);
  CarBandModel& widest = m.subspaces[1].bands[0];
  for (std::int8_t dc = -2; dc <= 1; ++dc) widest.neighbourhood.push_back({-3, dc});
  widest.gamma.assign(widest.neighbourhood.size(), 0.8f / static_cast<float>(widest.neighbourhood.size()));
  return m;
}

// HDR: subspace means and contrasts spread over 8 decades, as specular and dark measurements are.
Material hdr_material() {
  Material m = synthetic_material(3, 3);
  const float scales[] = {1e-4f, 1.0f, 1e4f};
  for (std::size_t s = 0; s < 3; ++s) {
    for (float& v : m.subspaces[s].colour_mean) v *= scales[s];
    for (float& v : m.subspaces[s].colour_transform) v *= scales[s];
  }
  return m;
}

void print_case(const CaseReport& r, double tolerance) {
  std::printf("\n%s: GPU %.1f ms, CPU float32 reference %.1f ms (1 thread)\n", r.name.c_str(), r.gpu_ms,
              r.cpu_ms);
  std::printf("  %-14s %6s %14s %14s %10s %8s\n", "stage", "items", "max err/std", "RMS err/std", "identical",
              "verdict");
  for (const StageResult& s : r.stages) {
    std::printf("  %-14s %6u %14.3e %14.3e %10s %8s\n", s.stage.c_str(), s.items, s.error.max_relative,
                s.error.rms_relative, s.identical ? "bits" : "no", s.error.within(tolerance) ? "ok" : "FAIL");
  }
  std::printf("  float32 (GPU) against the float64 reference: max %.3e, RMS %.3e of the std\n",
              r.float32_vs_float64.max_relative, r.float32_vs_float64.rms_relative);
}

void run_conform(const ConformOptions& options) {
  auto context = make_context(options.device);
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
  std::printf(
      "conformance on %s: GPU against the CPU float32 reference, seed %llu, margin %u; tolerance %.1e of "
      "each "
      "band's std (max abs error)\n",
      context->device_info().name.c_str(), static_cast<unsigned long long>(options.seed), options.margin,
      options.tolerance);
  std::vector<CaseReport> reports;
  auto run_and_print = [&](const std::string& name, const Material& m, std::uint32_t size) {
    std::printf("running %s...\n", name.c_str());
    std::fflush(stdout);
    reports.push_back(run_case(name, m, size, options, *synthesizer));
    print_case(reports.back(), options.tolerance);
    std::fflush(stdout);
  };
  if (!options.material.empty()) {
    Material material;
    check(read_material_file(options.material, material), "cannot read the material");
    run_and_print(
        options.material + " at " + std::to_string(options.size) + "x" + std::to_string(options.size),
        material, options.size);
  }
  if (options.extremes) {
    run_and_print("near-unit-root bands (spectral radius 0.99) at 1024x1024", near_unit_root_material(),
                  1024);
    run_and_print("largest neighbourhoods (12 and 16 neighbours), 3 levels, 512x512",
                  largest_neighbourhood_material(), 512);
    run_and_print("HDR: means and contrasts over 8 decades, 512x512", hdr_material(), 512);
    run_and_print("large: " + std::to_string(options.large_size) + "x" + std::to_string(options.large_size) +
                      ", 3 levels",
                  synthetic_material(1, 3), options.large_size);

    std::printf(
        "\nfloat32 error growth with field size, near-unit-root band, against float64 (GPU = CPU float32 "
        "where "
        "the stages above say bits):\n  %8s %14s %14s %10s\n",
        "size", "max err/std", "RMS err/std", "GPU bits");
    const Material stiff = near_unit_root_material();
    for (std::uint32_t size : options.growth_sizes) {
      SynthesisRequest request;
      request.seed = options.seed;
      request.width = request.height = size;
      request.margin = options.margin;
      // One whole-size copy of each kind at a time: the GPU's buffers go once its image is read back,
      // and its image once compared, before the float64 image (twice the size) is made.
      SynthesizedImages gpu;
      check(synthesizer->synthesize(stiff, request, gpu), "GPU synthesis failed");
      synthesizer->release();
      const SynthesisBlock& block = request;
      std::vector<float> f32(std::size_t{size} * size * 3);
      reference::synthesize_subspace(stiff, 0, block, f32);
      const bool gpu_bits = bitwise_equal(gpu.images[0], f32);
      gpu = {};
      std::vector<double> f64(f32.size());
      reference::synthesize_subspace(stiff, 0, block, f64);
      const ConformanceError e = reference::conformance_error(f32, f64, 3);
      std::printf("  %8u %14.3e %14.3e %10s\n", size, e.max_relative, e.rms_relative, gpu_bits ? "yes" : "NO");
      std::fflush(stdout);
    }
  }
  check_validation(*context);
  std::size_t failures = 0;
  for (const CaseReport& r : reports)
    for (const StageResult& s : r.stages) failures += s.error.within(options.tolerance) ? 0 : 1;
  if (failures > 0) {
    throw CommandError(std::to_string(failures) + " stage comparison(s) beyond the tolerance of " +
                       std::to_string(options.tolerance) + " of the std");
  }
  std::printf("\nall stages within %.1e of the std\n", options.tolerance);
}

}  // namespace

void register_conform_command(CLI::App& app) {
  auto options = std::make_shared<ConformOptions>();
  auto* command = app.add_subcommand(
      "conform",
      "Headless GPU-vs-CPU conformance of synthesis: every stage (noise, band fields, collapse, colour, "
      "interpolation) compared pixel by pixel, 2x2 blocks from stored initialization values against the "
      "whole, stiff and extreme cases, float32 error growth against float64; "
      "exits non-zero beyond the tolerance");
  command->add_option("material", options->material,
                      "Material file (.cbtf); without one only the built-in extreme cases run");
  command->add_option("--size", options->size, "Output size for the material")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed")->check(non_negative())->capture_default_str();
  command->add_option("--margin", options->margin, "CAR burn-in per level")
      ->check(CLI::Range(0u, 4096u))
      ->capture_default_str();
  command
      ->add_option(
          "--tolerance", options->tolerance,
          "Largest accepted max abs error, relative to each band's or channel's std (both sides follow one "
          "operation order, so the expected error is 0)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_flag("!--no-extremes", options->extremes, "Skip the built-in stiff and extreme cases");
  command->add_option("--large-size", options->large_size, "Size of the large extreme case")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command->add_option("--growth-sizes", options->growth_sizes, "Sizes of the float32 error-growth study")
      ->delimiter(',')
      ->check(CLI::Range(1u, 16384u));
  add_car_scheme_option(*command, options->scheme);
  add_device_options(*command, options->device);
  command->callback([options] { run_conform(*options); });
}

}  // namespace carbtf::cli
