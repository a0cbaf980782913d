// `carbtf demo`: the README's main job. For now it runs what exists end to end: a Gaussian noise
// field (the first synthesis stage) on the Vulkan device and on the CPU reference, checks that they
// agree bit for bit, measures both, and writes a report folder with pictures and figures.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <thread>
#include <vector>

#include "carbtf/analysis/field_statistics.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/reference/noise.hpp"
#include "carbtf/engine/noise_generator.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "report/html_report.hpp"

namespace carbtf::cli {

namespace {

struct DemoOptions {
  DeviceOptions device;
  std::string out = "carbtf-demo";
  std::uint32_t size = 512;
  std::uint64_t seed = 7;
};

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

void run_demo(const DemoOptions& options) {
  const std::filesystem::path folder = std::filesystem::absolute(options.out);
  create_folder(folder);
  const std::uint32_t n = options.size;

  std::printf("[1/3] Vulkan: noise field %ux%u, seed %llu\n", n, n, static_cast<unsigned long long>(options.seed));
  auto context = make_context(options.device);
  std::unique_ptr<NoiseGenerator> generator;
  check(NoiseGenerator::create(*context, generator), "cannot build the noise pipeline");
  std::vector<float> gpu;
  double kernel_ms = 0;
  auto start = std::chrono::steady_clock::now();
  check(generator->generate({options.seed, 0, 0, 0, n, n}, gpu, &kernel_ms), "noise generation failed");
  const double gpu_seconds = seconds_since(start);
  check_validation(*context);

  std::printf("[2/3] CPU reference\n");
  std::vector<float> cpu(gpu.size());
  start = std::chrono::steady_clock::now();
  reference::fill_noise_block(options.seed, 0, 0, 0, n, n, cpu);
  const double cpu_seconds = seconds_since(start);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < gpu.size(); ++i) mismatches += std::memcmp(&gpu[i], &cpu[i], sizeof(float)) != 0;

  std::printf("[3/3] report\n");
  write_field_image(folder / "noise.png", gpu, n, n);
  write_field_image(folder / "noise.exr", gpu, n, n);
  const FieldStatistics stats = field_statistics(gpu, n, n);

  // Histogram against the N(0,1) density.
  const int bins = 48;
  const double low = -4, high = 4, step = (high - low) / bins;
  std::vector<double> centres(bins), heights(bins, 0.0);
  for (int b = 0; b < bins; ++b) centres[b] = low + (b + 0.5) * step;
  for (float v : gpu) {
    const int b = static_cast<int>(std::floor((v - low) / step));
    if (b >= 0 && b < bins) heights[b] += 1.0;
  }
  for (double& h : heights) h /= static_cast<double>(gpu.size()) * step;
  std::vector<std::pair<double, double>> density;
  for (double x = low; x <= high + 1e-9; x += 0.05) density.emplace_back(x, std::exp(-0.5 * x * x) / std::sqrt(2 * std::numbers::pi));

  HtmlReport report("carbtf demo");
  report.paragraph("The pipeline so far: counter-based Gaussian noise, the first stage of CAR synthesis, "
                   "computed on the Vulkan device and by the CPU reference. Later stages (sample material, "
                   "analysis, synthesis, rendering) will join this report as they land.");
  report.heading("Noise field");
  report.image("noise.png", "field 0, seed " + std::to_string(options.seed) + "; grey maps [-4, 4] to [0, 255]");
  report.histogram_chart(centres, heights, density, "histogram of the GPU field (bars) and the N(0,1) density (line)");
  report.heading("Figures");
  report.table({{"figure", "value"},
                {"device", context->device_info().name + " (" + device_type_name(context->device_info().type) + ")"},
                {"size", std::to_string(n) + " x " + std::to_string(n)},
                {"GPU vs CPU: differing samples", std::to_string(mismatches) + " of " + std::to_string(gpu.size())},
                {"GPU kernel time (timestamps)", format("%.2f ms", kernel_ms)},
                {"GPU time with readback (wall)", format("%.2f ms", gpu_seconds * 1e3)},
                {"CPU reference time (" + std::to_string(std::thread::hardware_concurrency()) + " threads)",
                 format("%.2f ms", cpu_seconds * 1e3)},
                {"mean", format("%.5f", stats.mean)},
                {"variance", format("%.5f", stats.variance)},
                {"skewness", format("%.5f", stats.skewness)},
                {"excess kurtosis", format("%.5f", stats.excess_kurtosis)},
                {"lag-1 correlation, horizontal", format("%.5f", stats.lag1_horizontal)},
                {"lag-1 correlation, vertical", format("%.5f", stats.lag1_vertical)}});
  if (std::string error; !report.write(folder, error)) throw CommandError(error);

  std::printf("GPU and CPU agree on %zu of %zu samples; GPU kernel %.2f ms, CPU reference %.2f ms\n",
              gpu.size() - mismatches, gpu.size(), kernel_ms, cpu_seconds * 1e3);
  std::printf("report: %s\n", (folder / "index.html").c_str());
  if (mismatches != 0) throw CommandError("the GPU noise differs from the CPU reference");
}

}  // namespace

void register_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  auto* command = app.add_subcommand("demo", "Run the whole pipeline on built-in data and write an HTML report");
  command->add_option("--out", options->out, "Report folder")->capture_default_str();
  command->add_option("--size", options->size, "Field size in pixels")->check(CLI::Range(16u, 4096u))->capture_default_str();
  command->add_option("--seed", options->seed, "Seed")->check(non_negative())->capture_default_str();
  add_device_options(*command, options->device);
  command->callback([options] { run_demo(*options); });
}

}  // namespace carbtf::cli
