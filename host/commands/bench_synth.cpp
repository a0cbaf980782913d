// `carbtf bench synth`: error against run time of subspace-image synthesis. Sweeps output size, pyramid
// levels, neighbourhood size and subspace count one at a time around a base case, on the Vulkan device
// and on the CPU reference (bench/synthesis_bench.hpp measures), and writes what it measured as CSV,
// markdown and a PNG plot. Nothing here asserts a timing.
#include <cstdio>
#include <filesystem>

#include "bench/synthesis_bench.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "cli/cli_support.hpp"
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
  SynthesisBenchSettings settings;
};

// The sweeps, one parameter at a time around the base case; levels and neighbourhoods only for the
// synthetic materials (a loaded material has its own).
std::vector<SynthesisBenchCase> sweep_cases(const SynthBenchOptions& o, bool loaded) {
  std::vector<SynthesisBenchCase> cases;
  for (std::uint32_t size : o.sizes)
    cases.push_back({"size", size, o.base_levels, 0, o.size_sweep_subspaces});
  if (!loaded) {
    for (std::uint32_t levels : o.levels)
      cases.push_back({"levels", o.base_size, levels, 0, o.base_subspaces});
    for (std::uint32_t n : o.neighbours)
      cases.push_back({"neighbours", o.base_size, o.base_levels, n, o.base_subspaces});
  }
  for (std::uint32_t count : o.subspace_counts)
    cases.push_back({"subspaces", o.base_size, o.base_levels, 0, count});
  return cases;
}

void run_synth_bench(const SynthBenchOptions& options) {
  std::unique_ptr<Material> loaded;
  if (!options.material.empty()) {
    loaded = std::make_unique<Material>();
    check(read_material_file(options.material, *loaded), "cannot read the material");
  }
  std::unique_ptr<std::vector<RgbField>> measured;
  if (!options.btf.empty()) {
    if (!loaded)
      throw CommandError(
          "--btf needs --material: the fidelity error compares a material with its measured BTF");
    measured = std::make_unique<std::vector<RgbField>>(
        representative_images(load_measurement_of(*loaded, options.btf, "--btf"), *loaded));
  }
  auto context = make_context(options.device);
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
  const std::filesystem::path out = options.out;
  std::filesystem::create_directories(out);
  const SynthesisBenchSettings& s = options.settings;
  std::printf(
      "bench synth on %s (%s scheme), CPU reference on %u threads, median of %u GPU runs after a warm-up\n",
      context->device_info().name.c_str(), car_scheme_name(s.scheme), s.cpu_threads, s.repeats);
  std::printf("%-10s %5s %3s %5s %4s %9s %8s %7s %7s %7s %7s %9s %9s %10s %10s\n", "sweep", "size", "lvl",
              "nbrs", "subs", "scheme", "GPU ms", "frames", "CAR", "collapse", "colour", "wall ms", "CPU f32",
              "GPU err", "RMS err");
  std::vector<SynthesisBenchRow> rows;
  for (const SynthesisBenchCase& c : sweep_cases(options, loaded != nullptr)) {
    const SynthesisBenchRow row = run_synthesis_case(s, c, *synthesizer, loaded.get(), measured.get());
    std::printf("%-10s %5u %3u %5s %4u %9s %8.1f %7.1f %7.1f %7.1f %7.1f %9.1f %9.1f %10.2e %10.2e\n",
                c.sweep.c_str(), c.size, c.levels, neighbours_text(c.neighbours).c_str(),
                row.config.subspaces, row.scheme.c_str(), row.gpu_ms, row.gpu_prepare_ms, row.gpu_car_ms,
                row.gpu_collapse_ms, row.gpu_colour_ms, row.gpu_wall_ms, row.cpu_ms,
                row.gpu_error.max_relative, row.gpu_error.rms_relative);
    std::fflush(stdout);
    rows.push_back(row);
  }
  check_validation(*context);
  write_synthesis_bench_report(out, rows, context->device_info().name, s.cpu_threads, measured != nullptr);
  if (measured) {
    std::printf(
        "fidelity against the measured images (calibrated rel: 0 = as close as the measurement to itself, 1 "
        "= white "
        "noise; each synthesized subspace image against its representative pair's measured image):\n");
    for (const SynthesisBenchRow& r : rows) {
      std::printf("  %-10s %5u %4u subspaces, %u pairs: rel mean %.3f, worst %.3f; Gaussian reference %.3f\n",
                  r.config.sweep.c_str(), r.config.size, r.config.subspaces, r.fidelity.pairs,
                  r.fidelity.mean_rel, r.fidelity.worst_rel, r.fidelity.mean_gaussian_rel);
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
      ->add_option(
          "--btf", options->btf,
          "The measured BTF the --material was analysed from (folder, .zip or manifest): adds the "
          "fidelity error "
          "of docs/design.md 5 (calibrated rel of each subspace image against its measured pair) to each row")
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
  command
      ->add_option("--margin", options->settings.margin,
                   "The most CAR burn-in rows and columns a band gets (each takes what its stability needs, "
                   "docs/design.md 4.4)")
      ->check(CLI::Range(0u, 4096u))
      ->capture_default_str();
  command->add_option("--repeats", options->settings.repeats, "Timed GPU runs per case (median reported)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  command->add_option("--cpu-threads", options->settings.cpu_threads, "Threads of the CPU reference")
      ->check(CLI::Range(1u, 256u))
      ->capture_default_str();
  add_car_scheme_option(*command, options->settings.scheme);
  command->add_flag("--skip-cpu", options->settings.skip_cpu,
                    "Skip the CPU float32 timing (the float64 reference still runs)");
  add_device_options(*command, options->device);
  command->callback([options] { run_synth_bench(*options); });
}

}  // namespace carbtf::cli
