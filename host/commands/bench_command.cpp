// `carbtf bench ...`: benchmarks that print what they measured. Nothing here asserts a timing.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include <filesystem>

#include "carbtf/engine/synthesis/noise_generator.hpp"
#include "carbtf/reference/noise.hpp"
#include "cli/cli_support.hpp"
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
  const auto cpu_one = time_runs(
      options.repeats, [&](unsigned i) { reference::fill_noise_block(i + 2ull, 0, 0, 0, n, n, cpu, 1); });
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

}  // namespace

void register_bench_command(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "Benchmarks: print measured times and throughputs");
  bench->require_subcommand(1);
  auto options = std::make_shared<NoiseBenchOptions>();
  auto* noise =
      bench->add_subcommand("noise", "Gaussian noise throughput: GPU kernel, GPU with readback, CPU");
  noise->add_option("--size", options->size, "Field width and height")
      ->check(CLI::Range(16u, 8192u))
      ->capture_default_str();
  noise->add_option("--repeats", options->repeats, "Timed runs per path (median reported)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  add_device_options(*noise, options->device);
  noise->callback([options] { run_noise_bench(*options); });

  register_bench_data_command(*bench);
  register_bench_analyze_command(*bench);
  register_bench_synth_command(*bench);
  register_bench_fidelity_command(*bench);
  register_bench_frame_command(*bench);
}

}  // namespace carbtf::cli
