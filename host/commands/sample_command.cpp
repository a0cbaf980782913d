// `carbtf sample NAME`: renders a built-in sample material as a UBO2003 BTF plus its ground truth.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/btf/ubo2014_writer.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_btf.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {

namespace {

struct SampleOptions {
  std::string name;
  std::uint32_t size = 64;
  std::string out;
  std::string format = "jpg";
  bool zip = false;
  std::uint64_t seed = 1;
  std::uint32_t components = 64;
};

// The 81 x 81 images in memory, then one UBO2014 .btf file of them.
std::filesystem::path write_ubo2014_sample(const Surface& surface, const SampleOptions& options) {
  const std::filesystem::path path = std::filesystem::path(options.out) / "btf.btf";
  BtfDataset dataset(ubo2003_directions(), ubo2003_directions(), surface.size, surface.size,
                     ColorEncoding::linear_half);
  render_btf(surface, dataset.lights(), dataset.views(), {},
             [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
               dataset.set_linear({l, v}, image);
             });
  Ubo2014WriteOptions write;
  write.layout = options.format == "btf-raw" ? ubo2014::Layout::bdi : ubo2014::Layout::dfmf;
  write.components = options.components;
  write.colour_model = ubo2014::ColourModel::yuv;
  std::filesystem::create_directories(options.out);
  write_ubo2014_btf(path, dataset, write);
  return path;
}

void write_ground_truth(const Surface& surface, const std::filesystem::path& folder) {
  const std::uint32_t n = surface.size;
  write_field_image(folder / "range.exr", surface.height, n, n);
  const auto [lo, hi] = std::minmax_element(surface.height.begin(), surface.height.end());
  write_field_image(folder / "range.png", surface.height, n, n, {*lo, *hi});
  const std::vector<float> normals = surface_normals(surface);
  std::vector<float> encoded(normals.size());
  std::transform(normals.begin(), normals.end(), encoded.begin(), [](float v) { return 0.5f * v + 0.5f; });
  write_rgb_image(folder / "normals.exr", normals, n, n);
  write_rgb_image(folder / "normals.png", encoded, n, n, /*srgb_encode=*/false);
  write_rgb_image(folder / "albedo.exr", surface.albedo, n, n);
  write_rgb_image(folder / "albedo.png", surface.albedo, n, n);
}

void run_sample(const SampleOptions& options) {
  const std::filesystem::path out = options.out;
  const auto start = std::chrono::steady_clock::now();
  const Surface surface = make_sample_surface(options.name, options.size, options.seed);
  std::filesystem::path btf = out / (options.zip ? "btf.zip" : "btf");
  if (options.format.starts_with("btf")) {
    btf = write_ubo2014_sample(surface, options);
  } else {
    write_sample_btf(surface, btf, "." + options.format, options.zip);
  }
  write_ground_truth(surface, out / "ground_truth");
  std::ostringstream info;
  info << "{\n  \"material\": \"" << options.name << "\",\n  \"size\": " << options.size
       << ",\n  \"seed\": " << options.seed << ",\n  \"format\": \"" << options.format
       << "\",\n  \"height_units\": \"texels\",\n  \"specular\": " << surface.specular
       << ",\n  \"gloss\": " << surface.gloss << "\n}\n";
  write_output_file(out / "material.json", info.str());
  std::printf("wrote %s: %zu images of %ux%u (%s) in %.1f s; ground truth in %s\n", btf.c_str(),
              ubo2003_directions().size() * ubo2003_directions().size(), options.size, options.size,
              options.format.c_str(), seconds_since(start), (out / "ground_truth").c_str());
}

}  // namespace

void register_sample_command(CLI::App& app) {
  auto options = std::make_shared<SampleOptions>();
  std::string names;
  for (const std::string& n : sample_material_names()) names += (names.empty() ? "" : ", ") + n;
  auto* command =
      app.add_subcommand("sample",
                         "Render a sample material as a UBO2003 BTF (81 x 81 images) with its ground truth "
                         "(range map, normals, albedo)");
  command
      ->add_option(
          "name", options->name,
          "Material: " + (names.empty() ? std::string("(no recipes found)") : names) + ", or a recipe .json")
      ->required();
  command->add_option("--size", options->size, "Image width and height (64, 128 or 256 are typical)")
      ->check(CLI::Range(16u, 1024u))
      ->capture_default_str();
  command
      ->add_option("--out", options->out,
                   "Output folder: btf/ (or btf.zip, or btf.btf), ground_truth/, material.json")
      ->required();
  command
      ->add_option("--format", options->format,
                   "Image format; btf-dfmf and btf-raw write one Bonn UBO2014 file, btf.btf, in its DFMF "
                   "(factorised, YUV) or raw layout")
      ->check(CLI::IsMember({"jpg", "png", "exr", "btf-dfmf", "btf-raw"}))
      ->capture_default_str();
  command
      ->add_option("--components", options->components,
                   "btf-dfmf: components per colour channel (0: one per light/view pair, exact)")
      ->check(CLI::Range(0u, 6561u))
      ->capture_default_str();
  command->add_flag("--zip", options->zip, "Write the images into btf.zip instead of a folder");
  command->add_option("--seed", options->seed, "Seed of the procedural surface")
      ->check(non_negative())
      ->capture_default_str();
  command->callback([options] { run_sample(*options); });
}

}  // namespace carbtf::cli
