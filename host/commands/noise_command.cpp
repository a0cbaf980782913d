// `carbtf noise`: one Gaussian noise field, computed on a Vulkan device (or the CPU reference).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "carbtf/analysis/field_statistics.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/synthesis/noise_generator.hpp"
#include "carbtf/reference/noise.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {

namespace {

struct NoiseOptions {
  DeviceOptions device;
  std::uint32_t size = 1024;
  std::uint64_t seed = 7;
  std::uint32_t field = 0;
  std::string out = "noise.png";
  bool reference = false;
};

void run_noise(const NoiseOptions& options) {
  if (!is_supported_image_extension(options.out)) {
    throw CommandError(options.out +
                       ": unsupported image extension (use .png, .jpg, .bmp, .exr, .tif or .pfm)");
  }
  check_output_file_path(options.out, "--out");
  std::vector<float> values;
  const auto start = std::chrono::steady_clock::now();
  std::string where;
  if (options.reference) {
    values.resize(std::size_t{options.size} * options.size);
    reference::fill_noise_block(options.seed, options.field, 0, 0, options.size, options.size, values);
    where = "the CPU reference";
  } else {
    auto context = make_context(options.device);
    std::unique_ptr<NoiseGenerator> generator;
    check(NoiseGenerator::create(*context, generator), "cannot build the noise pipeline");
    check(generator->generate({options.seed, options.field, 0, 0, options.size, options.size}, values),
          "noise generation failed");
    check_validation(*context);
    where = context->device_info().name;
  }
  const double seconds = seconds_since(start);
  const FieldStatistics stats = field_statistics(values, options.size, options.size);
  write_field_image(options.out, values, options.size, options.size);
  std::printf("wrote %s: %ux%u N(0,1) field %u, seed %llu, on %s in %.1f ms (mean %.4f, std %.4f)%s\n",
              options.out.c_str(), options.size, options.size, options.field,
              static_cast<unsigned long long>(options.seed), where.c_str(), seconds * 1e3, stats.mean,
              std::sqrt(stats.variance),
              is_float_image_extension(options.out)
                  ? ""
                  : "; 8-bit files map [-4, 4] to [0, 255], .exr keeps the floats");
}

}  // namespace

void register_noise_command(CLI::App& app) {
  auto options = std::make_shared<NoiseOptions>();
  auto* command = app.add_subcommand(
      "noise", "Write one counter-based Gaussian noise field (the first stage of synthesis) as an image");
  command->add_option("--size", options->size, "Width and height in pixels")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed (64-bit)")->check(non_negative())->capture_default_str();
  command->add_option("--field", options->field, "Field id (each band of each subspace has its own)")
      ->check(non_negative())
      ->capture_default_str();
  command
      ->add_option("--out", options->out,
                   "Output image: .png/.jpg/.bmp (8-bit, [-4,4] -> [0,255]) or "
                   ".exr/.tif/.pfm (32-bit float)")
      ->capture_default_str();
  command->add_flag("--reference", options->reference, "Compute on the CPU reference instead of Vulkan");
  add_device_options(*command, options->device);
  command->callback([options] { run_noise(*options); });
}

}  // namespace carbtf::cli
