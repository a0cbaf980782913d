// `carbtf normals SET --out DIR`: photometric stereo on any set of one view under many lights.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <numeric>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "carbtf/analysis/range/photometric_stereo.hpp"
#include "carbtf/analysis/range/surface_integration.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct NormalsCommandOptions {
  std::string set;
  std::string out;
  std::string truth;
  int view = -1;
};

// A ground-truth normal map: 8- and 16-bit images encode n as (n + 1) / 2, float images hold n.
std::vector<float> read_truth(const std::string& path, std::uint32_t width, std::uint32_t height) {
  const RgbImage image = decode_rgb_image(path, read_file_bytes(path));
  if (image.width != width || image.height != height) {
    throw InputError(path, "normal map is " + std::to_string(image.width) + "x" +
                               std::to_string(image.height) + " but the images are " + std::to_string(width) +
                               "x" + std::to_string(height));
  }
  std::vector<float> normals(std::size_t{width} * height * 3);
  const bool float_file = is_float_image_extension(path);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const float v = image.linear ? image.linear_rgb[i] : image.srgb8[i] / 255.0f;
    normals[i] = float_file ? v : 2.0f * v - 1.0f;
  }
  return normals;
}

void run_normals(const NormalsCommandOptions& options) {
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(options.set, {}, warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (options.view >= static_cast<int>(dataset.views().size())) {
    throw CommandError("--view " + std::to_string(options.view) + " is out of range: the set has " +
                       std::to_string(dataset.views().size()) + " views");
  }
  const std::uint32_t view = options.view >= 0 ? static_cast<std::uint32_t>(options.view) : top_view(dataset);
  const NormalMap map = photometric_stereo(dataset, view);
  const Plane range = integrate_normals(map.normals, map.width, map.height);

  const fs::path out = options.out;
  create_folder(out);
  std::vector<float> encoded(map.normals.size());
  for (std::size_t i = 0; i < encoded.size(); ++i) encoded[i] = 0.5f * map.normals[i] + 0.5f;
  write_rgb_image(out / "normals.png", encoded, map.width, map.height, false);
  write_rgb_image(out / "normals.exr", map.normals, map.width, map.height);
  write_rgb_image(out / "albedo.png", map.albedo, map.width, map.height);
  const std::vector<float> heights(range.data(), range.data() + range.size());
  const auto [low, high] = std::minmax_element(heights.begin(), heights.end());
  write_field_image(out / "range_map.exr", heights, map.width, map.height);
  write_field_image(out / "range_map.png", heights, map.width, map.height,
                    {*low, std::max(*high, *low + 1e-6f)});
  const auto valid = std::count(map.valid.begin(), map.valid.end(), 1);
  std::printf("view %u, %zu lights: normals for %zd of %zu pixels; written to %s\n", view,
              dataset.lights().size(), static_cast<std::ptrdiff_t>(valid), map.valid.size(), out.c_str());

  if (!options.truth.empty()) {
    const std::vector<float> truth = read_truth(options.truth, map.width, map.height);
    std::vector<std::uint8_t> judged = map.valid;
    for (std::size_t i = 0; i < judged.size(); ++i) {
      if (!dataset.mask.empty() && dataset.mask[i] == 0) judged[i] = 0;
    }
    std::vector<double> errors = angular_errors_degrees(map.normals, truth, judged);
    if (errors.empty())
      throw CommandError("no pixel to compare with the ground truth (empty mask or no valid normals)");
    std::sort(errors.begin(), errors.end());
    const double mean =
        std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
    std::printf("angular error against %s over %zu pixels: mean %.2f deg, median %.2f deg\n",
                options.truth.c_str(), errors.size(), mean, errors[errors.size() / 2]);
  }
}

}  // namespace

void register_normals_command(CLI::App& app) {
  auto options = std::make_shared<NormalsCommandOptions>();
  auto* command = app.add_subcommand(
      "normals", "Photometric stereo: normal map, albedo and range map of one view under many lights");
  command
      ->add_option(
          "set", options->set,
          "A photometric-stereo folder (light_directions.txt, images, optional mask.png), or any BTF")
      ->required();
  command
      ->add_option("--out", options->out, "Output folder: normals.png/.exr, albedo.png, range_map.exr/.png")
      ->required();
  command->add_option("--truth", options->truth,
                      "Ground-truth normal map (x right, y up, z out; 8/16-bit images hold (n + 1) / 2, "
                      "float images n): prints the "
                      "mean and median angular error");
  command->add_option("--view", options->view, "View index (-1: the view nearest the surface normal)")
      ->check(CLI::Range(-1, 4095))
      ->capture_default_str();
  command->callback([options] { run_normals(*options); });
}

}  // namespace carbtf::cli
