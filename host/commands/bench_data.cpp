// `carbtf bench data`: how long datasets take to write and to load, and the memory they hold: a sample
// material as 81 x 81 UBO2003 JPEGs at 64^2 and 256^2, and as a synthetic 151 x 151 UBO2014 .btf file of
// 64^2 in each layout. Prints what it measured; asserts nothing.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <numbers>
#include <span>
#include <vector>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_writer.hpp"
#include "carbtf/analysis/btf/ubo2014_writer.hpp"
#include "carbtf/analysis/resource_usage.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "cli/cli_support.hpp"
#include "cli/owned_folder.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {

namespace {

struct DataBenchOptions {
  std::string material = "leather";
  std::string out = "carbtf-bench-data";
  std::vector<std::string> formats{"ubo2003", "ubo2014"};
  std::uint32_t components = 64;
  bool keep = false;
};

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / 1048576.0;
}

// Rendering a sample material at two sizes, then loading the full 81 x 81 JPEG set of the larger.
void run_ubo2003_bench(const DataBenchOptions& options, OwnedFolder& out) {
  std::printf("%-44s %10s\n", "step", "seconds");
  for (const std::uint32_t size : {64u, 256u}) {
    const auto start = std::chrono::steady_clock::now();
    const Surface surface = make_sample_surface(options.material, size, 1);
    Ubo2003Writer writer(out.claim("btf" + std::to_string(size)), ".jpg", false);
    const auto& directions = ubo2003_directions();
    std::chrono::steady_clock::duration encoding{};
    std::mutex mutex;
    render_btf(surface, directions, directions, {},
               [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
                 const auto encode_start = std::chrono::steady_clock::now();
                 writer.write(l, v, image, size, size);
                 std::lock_guard<std::mutex> lock(mutex);
                 encoding += std::chrono::steady_clock::now() - encode_start;
               });
    writer.finish();
    const std::string label = "render + write " + options.material + " " + std::to_string(size) + "x" +
                              std::to_string(size) + " (6561 JPEGs)";
    std::printf("%-44s %10.2f  (of which JPEG encode + write %.2f thread-s)\n", label.c_str(),
                seconds_since(start), std::chrono::duration<double>(encoding).count());
  }
  const double rss_before = mib(peak_rss_bytes());
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(out.root() / "btf256", {}, warnings);
  const double load_seconds = seconds_since(start);
  std::printf("%-44s %10.2f\n", "load 81x81 256x256 JPEGs", load_seconds);
  std::printf("pixel storage %.0f MiB; process peak RSS %.0f MiB (%.0f MiB before loading)\n\n",
              mib(dataset.storage_bytes()), mib(peak_rss_bytes()), rss_before);
}

// 151 directions in rings of 12 degrees (1, 6, 12, 18, 24, 30 and 60 azimuths): UBO2014's count, not
// its dome's exact directions, which the files carry themselves.
std::vector<Direction> dome_151_directions() {
  std::vector<Direction> directions;
  const int counts[] = {1, 6, 12, 18, 24, 30, 60};
  for (int ring = 0; ring < 7; ++ring) {
    for (int k = 0; k < counts[ring]; ++k)
      directions.push_back(Direction::from_degrees(12.0 * ring, 360.0 * k / counts[ring]));
  }
  return directions;
}

// Loads `path`, then reads every image once; peak resident memory over both, from a reset.
void time_ubo2014_load(const std::filesystem::path& path, const char* layout) {
  const bool reset = reset_peak_rss();
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(path, {}, warnings);
  const double load_seconds = seconds_since(start);
  const auto read_start = std::chrono::steady_clock::now();
  std::vector<float> rgb(dataset.pixel_count() * 3);
  double checksum = 0;
  for (const LightView pair : dataset.present_pairs()) {
    dataset.linear_rgb(pair, rgb);
    checksum += rgb[0];
  }
  std::printf("%-6s %10.0f %9.2f %14.2f %12.0f %12.0f  (checksum %.3f)\n", layout,
              mib(std::filesystem::file_size(path)), load_seconds, seconds_since(read_start),
              mib(dataset.storage_bytes()), reset ? mib(resident_high_water_bytes()) : NAN, checksum);
}

void run_ubo2014_bench(const DataBenchOptions& options, OwnedFolder& out) {
  constexpr std::uint32_t kSize = 64;
  const std::filesystem::path raw = out.claim("ubo2014_raw.btf");
  const std::filesystem::path dfmf = out.claim("ubo2014_dfmf.btf");
  {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<Direction> directions = dome_151_directions();
    BtfDataset dataset(directions, directions, kSize, kSize, ColorEncoding::linear_half);
    render_btf(make_sample_surface(options.material, kSize, 1), directions, directions, {},
               [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
                 dataset.set_linear({l, v}, image);
               });
    std::printf("%-44s %10.2f\n", "render 151x151 64x64 in memory", seconds_since(start));
    Ubo2014WriteOptions write;
    write.layout = ubo2014::Layout::bdi;
    const auto raw_start = std::chrono::steady_clock::now();
    write_ubo2014_btf(raw, dataset, write);
    std::printf("%-44s %10.2f\n", "write UBO2014 raw", seconds_since(raw_start));
    write.layout = ubo2014::Layout::dfmf;
    write.components = options.components;
    write.colour_model = ubo2014::ColourModel::yuv;
    const auto dfmf_start = std::chrono::steady_clock::now();
    write_ubo2014_btf(dfmf, dataset, write);
    const std::string label =
        "write UBO2014 DFMF (" + std::to_string(options.components) + " components, YUV)";
    std::printf("%-44s %10.2f\n\n", label.c_str(), seconds_since(dfmf_start));
  }
  std::printf("%-6s %10s %9s %14s %12s %12s\n", "layout", "file MiB", "load s", "read all s", "held MiB",
              "peak MiB");
  time_ubo2014_load(dfmf, "DFMF");
  time_ubo2014_load(raw, "raw");
}

void run_data_bench(const DataBenchOptions& options) {
  OwnedFolder out(options.out);
  if (options.keep) out.keep();
  for (const std::string& format : options.formats) {
    if (format == "ubo2003") run_ubo2003_bench(options, out);
    if (format == "ubo2014") run_ubo2014_bench(options, out);
  }
}

}  // namespace

void register_bench_data_command(CLI::App& bench) {
  auto options = std::make_shared<DataBenchOptions>();
  auto* data =
      bench.add_subcommand("data",
                           "Dataset write and load: a sample material as 81x81 UBO2003 JPEGs (render at 64 "
                           "and 256, then load time and "
                           "peak RSS of the 256x256 set), and as a synthetic 151x151 UBO2014 .btf of 64x64 "
                           "in each layout (load time, "
                           "time to read every image, memory held and peak resident memory of each)");
  data->add_option("--material", options->material, "Sample material to render")->capture_default_str();
  data->add_option("--formats", options->formats, "Which parts to run")
      ->check(CLI::IsMember({"ubo2003", "ubo2014"}))
      ->delimiter(',')
      ->capture_default_str();
  data->add_option("--components", options->components, "Components per colour channel of the DFMF file")
      ->check(CLI::Range(1u, 1024u))
      ->capture_default_str();
  data->add_option(
          "--out", options->out,
          "Folder for the written data (created if missing; only what the bench creates there is removed)")
      ->capture_default_str();
  data->add_flag("--keep", options->keep, "Keep the written data instead of deleting it");
  data->callback([options] { run_data_bench(*options); });
}

}  // namespace carbtf::cli
