// `carbtf bench synth`: error against run time of subspace-image synthesis. Sweeps output size, pyramid
// levels, neighbourhood size and subspace count one at a time around a base case, on the Vulkan device
// and on the CPU reference, and writes what it measured as CSV, markdown and a PNG plot. Nothing here
// asserts a timing.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/analysis/quality/texture_similarity.hpp"
#include "carbtf/reference/conformance.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "carbtf/analysis/report/figures.hpp"
#include "carbtf/reference/synthetic_material.hpp"
#include "carbtf/engine/material_file.hpp"
#include "carbtf/engine/range_tiles.hpp"
#include "carbtf/engine/subspace_synthesizer.hpp"
#include "cli/cli_support.hpp"
#include "cli/measurement.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {
namespace {

struct SynthBenchOptions {
  DeviceOptions device;
  std::string material;  // empty: synthetic materials
  std::string btf;       // the material's measured BTF: fidelity error against it
  std::string out = "carbtf-bench-synth";
  std::vector<std::uint32_t> sizes = {128, 256, 512, 1024, 2048};
  std::vector<std::uint32_t> levels = {1, 2, 3};
  std::vector<std::uint32_t> neighbours = {1, 2, 4, 6, 12};
  std::vector<std::uint32_t> subspace_counts = {1, 5, 10, 20};
  std::uint32_t base_size = 512;
  std::uint32_t base_levels = 3;
  std::uint32_t base_subspaces = 20;
  std::uint32_t size_sweep_subspaces = 5;
  std::uint32_t margin = 64;
  unsigned repeats = 5;
  unsigned cpu_threads = 2;
  CarScheme scheme = CarScheme::automatic;
  bool skip_cpu = false;
};

struct BenchCase {
  std::string sweep;
  std::uint32_t size = 512;
  std::uint32_t levels = 3;
  std::uint32_t neighbours = 0;  // 0: the material's own / mixed shapes
  std::uint32_t subspaces = 20;
};

struct FidelityColumn {
  std::uint32_t pairs = 0;
  double mean_rel = 0.0, worst_rel = 0.0, mean_gaussian_rel = 0.0;
};

struct BenchRow {
  BenchCase config;
  std::string scheme;
  double gpu_ms = 0.0;           // median GPU timestamps, whole synthesis
  double gpu_prepare_ms = 0.0;   // of which the frames (car_prepare),
  double gpu_car_ms = 0.0;       // the recursions with their noise,
  double gpu_collapse_ms = 0.0;  // the pyramid collapse
  double gpu_colour_ms = 0.0;    // and the colour transform
  double gpu_wall_ms = 0.0;      // median wall time including submit, wait and readback
  double cpu_ms = 0.0;           // CPU float32 reference on cpu_threads threads
  double cpu64_ms = 0.0;         // CPU float64 reference (the accuracy reference)
  reference::ConformanceError gpu_error;
  reference::ConformanceError cpu_error;
  FidelityColumn fidelity;  // of the GPU images against the measured pairs they represent (pairs 0: none)
  std::uint32_t batches = 0;
  std::uint32_t dispatches = 0;
};

// The measured images the fidelity is scored against: each subspace's representative pair, the
// measured image its model was fitted to.
struct MeasuredImages {
  std::vector<RgbField> images;  // per subspace, linear RGB
};

MeasuredImages measure_dataset(const std::string& path, const Material& material) {
  const BtfDataset dataset = load_measurement_of(material, path, "--btf");
  MeasuredImages measured;
  for (const SubspaceModel& s : material.subspaces) {
    if (!dataset.has_image({s.light, s.view})) {
      throw CommandError("--btf " + path + ": the image of light " + std::to_string(s.light) + " view " + std::to_string(s.view) + " is missing");
    }
    RgbField image{std::vector<float>(dataset.pixel_count() * 3), dataset.width(), dataset.height()};
    dataset.linear_rgb({s.light, s.view}, image.rgb);
    measured.images.push_back(std::move(image));
  }
  return measured;
}

// The calibrated fidelity (DESIGN.md 5, analysis/quality/texture_similarity) of each synthesized
// subspace image against the measured image of its representative pair. The model image is the
// subspace image times the enlarged relief tone and relit range map (apply_relief): the render pass at
// the pair's own directions without parallax or interpolation, so the column follows the synthesis
// alone; `carbtf fidelity` scores the whole render pass.
FidelityColumn fidelity_of(const Material& material, const SynthesizedImages& images, const MeasuredImages& measured) {
  const std::uint32_t w = images.width, h = images.height;
  std::vector<float> heights(std::size_t{w} * h, 0.0f), tones(heights.size(), 1.0f);
  if (material.range.tile_size > 0) {
    enlarge_range_map(material.range, 1, 0, 0, w, h, heights);
    enlarge_range_map(material.range, 1, 0, 0, w, h, tones, RangeChannel::tone);
  }
  Plane height_plane(h, w), tone(h, w);
  for (std::size_t p = 0; p < heights.size(); ++p) {
    height_plane(static_cast<Eigen::Index>(p / w), static_cast<Eigen::Index>(p % w)) = heights[p];
    tone(static_cast<Eigen::Index>(p / w), static_cast<Eigen::Index>(p % w)) = tones[p];
  }
  FidelityColumn column;
  for (std::size_t s = 0; s < measured.images.size() && s < images.images.size(); ++s) {
    if (images.images[s].empty() || material.subspaces[s].channels != 3) continue;
    const MaterialDirection& l = material.lights[material.subspaces[s].light];
    const std::array<double, 3> light{std::sin(l.theta) * std::cos(l.phi), std::sin(l.theta) * std::sin(l.phi), std::cos(l.theta)};
    RgbField model{images.images[s], w, h};
    apply_relief(model.rgb, weighted_tone(tone, material.subspaces[s].tone_weight, material.range.tone_chroma),
                 relit_factor(height_plane, light, relight_floor(material)));
    const CalibratedFidelity f = calibrated_fidelity(model, measured.images[s]);
    column.mean_rel += f.rel;
    column.mean_gaussian_rel += f.gaussian_rel;
    column.worst_rel = column.pairs == 0 ? f.rel : std::max(column.worst_rel, f.rel);
    ++column.pairs;
  }
  if (column.pairs > 0) {
    column.mean_rel /= column.pairs;
    column.mean_gaussian_rel /= column.pairs;
  }
  return column;
}

// The material of a case and the subspaces to synthesize: the first `c.subspaces` of the loaded material
// (the whole material, so that its index table stays valid), or a synthetic one with the case's shape.
Material material_for(const BenchCase& c, const Material* loaded, std::vector<std::uint32_t>& subspaces) {
  subspaces.clear();
  if (!loaded) return synthetic_material(c.subspaces, c.levels, 3, c.neighbours);
  const auto count = static_cast<std::uint32_t>(std::min<std::size_t>(loaded->subspaces.size(), c.subspaces));
  for (std::uint32_t s = 0; s < count; ++s) subspaces.push_back(s);
  return *loaded;
}

BenchRow run_case(const SynthBenchOptions& options, const BenchCase& c, SubspaceSynthesizer& synthesizer,
                  const Material* loaded, const MeasuredImages* measured) {
  std::vector<std::uint32_t> subspaces;
  const Material material = material_for(c, loaded, subspaces);
  SynthesisRequest request;
  request.seed = 1;
  request.width = request.height = c.size;
  request.margin = options.margin;
  request.scheme = options.scheme;
  request.subspaces = subspaces;
  BenchRow row;
  row.config = c;
  row.config.subspaces =
      static_cast<std::uint32_t>(subspaces.empty() ? material.subspaces.size() : subspaces.size());

  SynthesizedImages images;
  check(synthesizer.synthesize(material, request, images), "synthesis failed");  // warm-up
  std::vector<double> gpu, prepare, car, collapse, colour, wall;
  for (unsigned i = 0; i < options.repeats; ++i) {
    SynthesisTiming timing;
    const auto start = std::chrono::steady_clock::now();
    check(synthesizer.synthesize(material, request, images, &timing), "synthesis failed");
    wall.push_back(seconds_since(start) * 1e3);
    gpu.push_back(timing.total_ms);
    prepare.push_back(timing.prepare_ms);
    car.push_back(timing.car_ms);
    collapse.push_back(timing.collapse_ms);
    colour.push_back(timing.colour_ms);
    row.batches = timing.batches;
    row.dispatches = timing.dispatches;
  }
  row.scheme = car_scheme_name(synthesizer.scheme());
  row.gpu_ms = median(gpu);
  row.gpu_prepare_ms = median(prepare);
  row.gpu_car_ms = median(car);
  row.gpu_collapse_ms = median(collapse);
  row.gpu_colour_ms = median(colour);
  row.gpu_wall_ms = median(wall);

  const SynthesisBlock& block = request;
  auto start = std::chrono::steady_clock::now();
  const auto f64 = reference::synthesize_subspaces_f64(material, subspaces, block, options.cpu_threads);
  row.cpu64_ms = seconds_since(start) * 1e3;
  std::vector<std::vector<float>> f32;
  if (!options.skip_cpu) {
    start = std::chrono::steady_clock::now();
    f32 = reference::synthesize_subspaces(material, subspaces, block, options.cpu_threads);
    row.cpu_ms = seconds_since(start) * 1e3;
  }
  for (std::size_t s = 0; s < material.subspaces.size(); ++s) {
    if (images.images[s].empty()) continue;
    const std::uint32_t channels = material.subspaces[s].channels;
    row.gpu_error =
        reference::worst_of(row.gpu_error, reference::conformance_error(images.images[s], f64[s], channels));
    if (!f32.empty()) {
      row.cpu_error =
          reference::worst_of(row.cpu_error, reference::conformance_error(f32[s], f64[s], channels));
    }
  }
  if (measured) row.fidelity = fidelity_of(material, images, *measured);
  return row;
}

std::string neighbours_text(std::uint32_t n) {
  return n == 0 ? "mixed" : std::to_string(n);
}

void write_tables(const std::filesystem::path& out, const std::vector<BenchRow>& rows,
                  const std::string& device, unsigned threads) {
  std::ofstream csv(out / "bench_synth.csv");
  csv << "sweep,size,levels,neighbours,subspaces,scheme,batches,dispatches,gpu_ms,gpu_prepare_ms,gpu_car_ms,"
         "gpu_collapse_ms,gpu_colour_ms,gpu_wall_ms,cpu_f32_ms,cpu_f64_ms,"
         "gpu_max_err_over_std,gpu_rms_err_over_std,cpu_f32_max_err_over_std,cpu_f32_rms_err_over_std,"
         "fidelity_pairs,rel_mean,rel_worst,gaussian_rel_mean\n";
  std::ofstream md(out / "bench_synth.md");
  md << "# carbtf bench synth\n\nDevice: " << device << ". CPU reference on " << threads
     << " threads. Errors are against the float64 CPU reference, relative to each channel's standard "
        "deviation"
     << ". Fidelity is the calibrated texture-similarity rel (DESIGN.md 5; 0 = as close as the measurement "
        "to itself, 1 = white noise) of the GPU images, times the relief tone and the relit range map, against "
        "the measured image of each subspace's representative pair, mean (worst), beside the best Gaussian "
        "texture's.\n\n"
     << "| sweep | size | levels | neighbours | subspaces | scheme | GPU ms | frames | CAR with noise | "
        "collapse | "
        "colour | GPU wall ms | "
        "CPU f32 ms | CPU f64 ms | GPU max err/std | GPU RMS err/std | CPU f32 max err/std | pairs | rel | "
        "Gaussian rel |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchRow& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s,%u,%u,%s,%u,%s,%u,%u,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3e,%.3e,%.3e,%.3e\n",
                  r.config.sweep.c_str(), r.config.size, r.config.levels,
                  neighbours_text(r.config.neighbours).c_str(), r.config.subspaces, r.scheme.c_str(),
                  r.batches, r.dispatches, r.gpu_ms, r.gpu_prepare_ms, r.gpu_car_ms, r.gpu_collapse_ms,
                  r.gpu_colour_ms, r.gpu_wall_ms, r.cpu_ms, r.cpu64_ms, r.gpu_error.max_relative,
                  r.gpu_error.rms_relative, r.cpu_error.max_relative, r.cpu_error.rms_relative);
    csv << std::string(line, std::strlen(line) - 1);  // the fidelity columns follow
    const FidelityColumn& f = r.fidelity;
    std::snprintf(line, sizeof line, ",%u,%.4f,%.4f,%.4f\n", f.pairs, f.mean_rel, f.worst_rel, f.mean_gaussian_rel);
    csv << line;
    std::snprintf(line, sizeof line,
                  "| %s | %u | %u | %s | %u | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | "
                  "%.2e | %.2e | %.2e |",
                  r.config.sweep.c_str(), r.config.size, r.config.levels,
                  neighbours_text(r.config.neighbours).c_str(), r.config.subspaces, r.scheme.c_str(),
                  r.gpu_ms, r.gpu_prepare_ms, r.gpu_car_ms, r.gpu_collapse_ms, r.gpu_colour_ms, r.gpu_wall_ms,
                  r.cpu_ms, r.cpu64_ms, r.gpu_error.max_relative, r.gpu_error.rms_relative,
                  r.cpu_error.max_relative);
    md << line;
    if (f.pairs == 0) {
      md << " - | - | - |\n";
    } else {
      std::snprintf(line, sizeof line, " %u | %.3f (%.3f) | %.3f |\n", f.pairs, f.mean_rel, f.worst_rel, f.mean_gaussian_rel);
      md << line;
    }
  }
}

void run_synth_bench(const SynthBenchOptions& options) {
  std::unique_ptr<Material> loaded;
  if (!options.material.empty()) {
    loaded = std::make_unique<Material>();
    check(read_material_file(options.material, *loaded), "cannot read the material");
  }
  std::unique_ptr<MeasuredImages> measured;
  if (!options.btf.empty()) {
    if (!loaded)
      throw CommandError(
          "--btf needs --material: the fidelity error compares a material with its measured BTF");
    measured = std::make_unique<MeasuredImages>(measure_dataset(options.btf, *loaded));
  }
  std::vector<BenchCase> cases;
  for (std::uint32_t size : options.sizes)
    cases.push_back({"size", size, options.base_levels, 0, options.size_sweep_subspaces});
  if (!loaded) {
    for (std::uint32_t levels : options.levels)
      cases.push_back({"levels", options.base_size, levels, 0, options.base_subspaces});
    for (std::uint32_t n : options.neighbours)
      cases.push_back({"neighbours", options.base_size, options.base_levels, n, options.base_subspaces});
  }
  for (std::uint32_t count : options.subspace_counts)
    cases.push_back({"subspaces", options.base_size, options.base_levels, 0, count});

  auto context = make_context(options.device);
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
  const std::filesystem::path out = options.out;
  std::filesystem::create_directories(out);
  std::printf(
      "bench synth on %s (%s scheme), CPU reference on %u threads, median of %u GPU runs after a warm-up\n",
      context->device_info().name.c_str(), car_scheme_name(options.scheme), options.cpu_threads,
      options.repeats);
  std::printf("%-10s %5s %3s %5s %4s %9s %8s %7s %7s %7s %7s %9s %9s %10s %10s\n", "sweep", "size", "lvl",
              "nbrs", "subs", "scheme", "GPU ms", "frames", "CAR", "collapse", "colour", "wall ms", "CPU f32",
              "GPU err", "RMS err");
  std::vector<BenchRow> rows;
  for (const BenchCase& c : cases) {
    const BenchRow row = run_case(options, c, *synthesizer, loaded.get(), measured.get());
    std::printf("%-10s %5u %3u %5s %4u %9s %8.1f %7.1f %7.1f %7.1f %7.1f %9.1f %9.1f %10.2e %10.2e\n",
                c.sweep.c_str(), c.size, c.levels, neighbours_text(c.neighbours).c_str(),
                row.config.subspaces, row.scheme.c_str(), row.gpu_ms, row.gpu_prepare_ms, row.gpu_car_ms,
                row.gpu_collapse_ms, row.gpu_colour_ms, row.gpu_wall_ms, row.cpu_ms,
                row.gpu_error.max_relative, row.gpu_error.rms_relative);
    std::fflush(stdout);
    rows.push_back(row);
  }
  check_validation(*context);
  write_tables(out, rows, context->device_info().name, options.cpu_threads);

  std::vector<ScatterPoint> points;
  for (const BenchRow& r : rows) {
    points.push_back({r.gpu_ms, std::max(r.gpu_error.max_relative, 1e-9), 0});
    if (r.cpu_ms > 0) points.push_back({r.cpu_ms, std::max(r.cpu_error.max_relative, 1e-9), 1});
  }
  const std::string device_entry = "GPU: " + context->device_info().name.substr(0, 40);
  const std::string cpu_entry = "CPU REFERENCE, " + std::to_string(options.cpu_threads) + " THREADS";
  const std::string_view legend[] = {device_entry, cpu_entry};
  const Figure plot = scatter_figure(points, "RUN TIME (MS)", "MAX ERROR / STD AGAINST FLOAT64", legend);
  write_rgb_image((out / "bench_synth.png").string(), plot.rgb, plot.width, plot.height, false);
  if (measured) {
    std::vector<ScatterPoint> fidelity;
    for (const BenchRow& r : rows) {
      if (r.fidelity.pairs > 0) fidelity.push_back({r.gpu_ms, std::max(r.fidelity.mean_rel, 1e-3), 0});
    }
    const std::string_view fidelity_legend[] = {device_entry};
    const Figure figure = scatter_figure(fidelity, "RUN TIME (MS)",
                                         "MEAN REL AGAINST THE MEASURED IMAGES", fidelity_legend);
    write_rgb_image((out / "bench_synth_fidelity.png").string(), figure.rgb, figure.width, figure.height,
                    false);
    std::printf("fidelity against the measured images (calibrated rel: 0 = as close as the measurement to itself, 1 = white "
                "noise; each synthesized subspace image against its representative pair's measured image):\n");
    for (const BenchRow& r : rows) {
      std::printf("  %-10s %5u %4u subspaces, %u pairs: rel mean %.3f, worst %.3f; Gaussian reference %.3f\n",
                  r.config.sweep.c_str(), r.config.size, r.config.subspaces, r.fidelity.pairs, r.fidelity.mean_rel,
                  r.fidelity.worst_rel, r.fidelity.mean_gaussian_rel);
    }
    std::printf("bench_synth_fidelity.png plots mean rel against run time\n");
  }
  std::printf("wrote %s/bench_synth.csv, bench_synth.md and bench_synth.png (error against run time)\n",
              out.string().c_str());
}

}  // namespace

void register_bench_synth_command(CLI::App& bench) {
  auto options = std::make_shared<SynthBenchOptions>();
  auto* command =
      bench.add_subcommand("synth",
                           "Error against run time of subspace synthesis: sweeps size, levels, neighbourhood "
                           "size and subspace count "
                           "on the Vulkan device and the CPU reference; writes CSV, markdown and a PNG plot");
  command->add_option("--material", options->material,
                      "A .cbtf material to synthesize (default: synthetic materials with known stable bands, "
                      "which also allow "
                      "the levels and neighbourhood sweeps)");
  command
      ->add_option("--btf", options->btf,
                   "The measured BTF the --material was analysed from (folder, .zip or manifest): adds the "
                   "fidelity error "
                   "of DESIGN.md 5 (calibrated rel of each subspace image against its measured pair) to each row")
      ->check(CLI::ExistingPath);
  command->add_option("--out", options->out, "Folder for bench_synth.csv, .md and .png")
      ->capture_default_str();
  command->add_option("--sizes", options->sizes, "Output sizes of the size sweep")
      ->delimiter(',')
      ->check(CLI::Range(1u, 16384u));
  command->add_option("--levels", options->levels, "Pyramid levels of the levels sweep")
      ->delimiter(',')
      ->check(CLI::Range(1u, 3u));
  command
      ->add_option("--neighbours", options->neighbours,
                   "Neighbourhood sizes of the neighbourhood sweep (1, 2, 4, 6, 12)")
      ->delimiter(',')
      ->check(CLI::IsMember({1u, 2u, 4u, 6u, 12u}));
  command->add_option("--subspace-counts", options->subspace_counts, "Subspace counts of the subspace sweep")
      ->delimiter(',')
      ->check(CLI::Range(1u, 255u));
  command
      ->add_option("--base-size", options->base_size, "Size of the levels, neighbourhood and subspace sweeps")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command
      ->add_option("--base-subspaces", options->base_subspaces,
                   "Subspaces in the levels and neighbourhood sweeps")
      ->check(CLI::Range(1u, 255u))
      ->capture_default_str();
  command->add_option("--size-sweep-subspaces", options->size_sweep_subspaces, "Subspaces in the size sweep")
      ->check(CLI::Range(1u, 255u))
      ->capture_default_str();
  command->add_option("--margin", options->margin, "CAR burn-in margin per level")
      ->check(CLI::Range(0u, 4096u))
      ->capture_default_str();
  command->add_option("--repeats", options->repeats, "Timed GPU runs per case (median reported)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  command->add_option("--cpu-threads", options->cpu_threads, "Threads of the CPU reference")
      ->check(CLI::Range(1u, 256u))
      ->capture_default_str();
  add_car_scheme_option(*command, options->scheme);
  command->add_flag("--skip-cpu", options->skip_cpu,
                    "Skip the CPU float32 timing (the float64 reference still runs)");
  add_device_options(*command, options->device);
  command->callback([options] { run_synth_bench(*options); });
}

}  // namespace carbtf::cli
