// `carbtf bench ...`: benchmarks that print what they measured. Nothing here asserts a timing.
#include <algorithm>
#include <mutex>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include <filesystem>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_writer.hpp"
#include "carbtf/reference/noise.hpp"
#include "carbtf/analysis/resource_usage.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/synthesis/noise_generator.hpp"
#include "cli/cli_support.hpp"
#include "cli/owned_folder.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {

namespace {

struct NoiseBenchOptions {
  DeviceOptions device;
  std::uint32_t size = 1024;
  unsigned repeats = 5;
};

template <typename Run>
std::vector<double> time_runs(unsigned repeats, Run&& run) {
  std::vector<double> seconds;
  for (unsigned i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    run(i);
    seconds.push_back(seconds_since(start));
  }
  return seconds;
}

void run_noise_bench(const NoiseBenchOptions& options) {
  const std::uint32_t n = options.size;
  const double samples = static_cast<double>(n) * n;
  auto context = make_context(options.device);
  std::unique_ptr<NoiseGenerator> generator;
  check(NoiseGenerator::create(*context, generator), "cannot build the noise pipeline");
  std::vector<float> values;
  std::vector<double> kernel_ms;
  // One warm-up run: pipeline compilation and first-touch allocation are not throughput.
  check(generator->generate({1, 0, 0, 0, n, n}, values), "noise generation failed");
  const auto gpu_wall = time_runs(options.repeats, [&](unsigned i) {
    double ms = 0;
    check(generator->generate({i + 2ull, 0, 0, 0, n, n}, values, &ms), "noise generation failed");
    kernel_ms.push_back(ms);
  });
  check_validation(*context);

  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<float> cpu(std::size_t{n} * n);
  const auto cpu_one = time_runs(options.repeats, [&](unsigned i) {
    reference::fill_noise_block(i + 2ull, 0, 0, 0, n, n, cpu, 1);
  });
  const auto cpu_all = time_runs(options.repeats, [&](unsigned i) {
    reference::fill_noise_block(i + 2ull, 0, 0, 0, n, n, cpu, threads);
  });

  const double kernel = median(kernel_ms) * 1e-3;
  std::printf("noise %ux%u, median of %u runs, device %s\n", n, n, options.repeats,
              context->device_info().name.c_str());
  std::printf("%-34s %10s %14s\n", "path", "ms", "Msamples/s");
  auto row = [&](const char* name, double s) {
    std::printf("%-34s %10.2f %14.1f\n", name, s * 1e3, samples / s * 1e-6);
  };
  if (kernel > 0) row("GPU kernel (timestamps)", kernel);
  row("GPU with readback (wall)", median(gpu_wall));
  row("CPU reference, 1 thread", median(cpu_one));
  const std::string all = "CPU reference, " + std::to_string(threads) + " threads";
  row(all.c_str(), median(cpu_all));
  if (kernel > 0) {
    std::printf("GPU kernel / CPU %u threads throughput ratio: %.2f\n", threads, median(cpu_all) / kernel);
  }
}

struct DataBenchOptions {
  std::string material = "leather";
  std::string out = "carbtf-bench-data";
  bool keep = false;
};

double peak_rss_mib() { return static_cast<double>(peak_rss_bytes()) / 1048576.0; }

// Rendering a sample material at two sizes, then loading the full 81 x 81 JPEG set of the larger.
void run_data_bench(const DataBenchOptions& options) {
  OwnedFolder out(options.out);
  if (options.keep) out.keep();
  std::printf("%-44s %10s\n", "step", "seconds");
  for (const std::uint32_t size : {64u, 256u}) {
    const auto start = std::chrono::steady_clock::now();
    const Surface surface = make_sample_surface(options.material, size, 1);
    Ubo2003Writer writer(out.claim("btf" + std::to_string(size)), ".jpg", false);
    const auto& directions = ubo2003_directions();
    RenderOptions render;
    std::chrono::steady_clock::duration encoding{};
    std::mutex mutex;
    render_btf(surface, directions, directions, render, [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
      const auto encode_start = std::chrono::steady_clock::now();
      writer.write(l, v, image, size, size);
      std::lock_guard<std::mutex> lock(mutex);
      encoding += std::chrono::steady_clock::now() - encode_start;
    });
    writer.finish();
    const std::string label = "render + write " + options.material + " " + std::to_string(size) + "x" +
                              std::to_string(size) + " (6561 JPEGs)";
    std::printf("%-44s %10.2f  (of which JPEG encode + write %.2f thread-s)\n", label.c_str(), seconds_since(start),
                std::chrono::duration<double>(encoding).count());
  }
  const double rss_before = peak_rss_mib();
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(out.root() / "btf256", {}, warnings);
  const double load_seconds = seconds_since(start);
  std::printf("%-44s %10.2f\n", "load 81x81 256x256 JPEGs", load_seconds);
  std::printf("pixel storage %.0f MiB; process peak RSS %.0f MiB (%.0f MiB before loading)\n",
              dataset.storage_bytes() / 1048576.0, peak_rss_mib(), rss_before);
}

}  // namespace

void register_bench_command(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "Benchmarks: print measured times and throughputs");
  bench->require_subcommand(1);
  auto options = std::make_shared<NoiseBenchOptions>();
  auto* noise = bench->add_subcommand("noise", "Gaussian noise throughput: GPU kernel, GPU with readback, CPU");
  noise->add_option("--size", options->size, "Field width and height")->check(CLI::Range(16u, 8192u))->capture_default_str();
  noise->add_option("--repeats", options->repeats, "Timed runs per path (median reported)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  add_device_options(*noise, options->device);
  noise->callback([options] { run_noise_bench(*options); });

  auto data_options = std::make_shared<DataBenchOptions>();
  auto* data = bench->add_subcommand("data", "Sample rendering at 64 and 256, then load time and peak RSS of the "
                                             "full 81x81 256x256 JPEG material");
  data->add_option("--material", data_options->material, "Sample material to render")->capture_default_str();
  data->add_option("--out", data_options->out, "Folder for the rendered images (created if missing; only what the bench creates there is removed)")->capture_default_str();
  data->add_flag("--keep", data_options->keep, "Keep the rendered images instead of deleting them");
  data->callback([data_options] { run_data_bench(*data_options); });

  register_bench_analyze_command(*bench);
  register_bench_synth_command(*bench);
  register_bench_fidelity_command(*bench);
  register_bench_frame_command(*bench);
}

}  // namespace carbtf::cli
