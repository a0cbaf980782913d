// `carbtf bench analyze`: analysis time per stage, peak RSS, file size and compression ratio for each
// sample material. Each analysis runs in a child process, so its peak RSS is its own.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_writer.hpp"
#include "carbtf/analysis/resource_usage.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "cli/cli_support.hpp"
#include "cli/owned_folder.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct AnalyzeBenchOptions {
  std::vector<std::string> materials;
  std::vector<std::uint32_t> sizes{128, 256};
  std::string out = "carbtf-bench-analyze";
  bool keep = false;
};

void render_jpeg_btf(const std::string& material, std::uint32_t size, const fs::path& folder) {
  const Surface surface = make_sample_surface(material, size, 1);
  Ubo2003Writer writer(folder, ".jpg", false);
  RenderOptions render;
  render.progress = false;
  render_btf(surface, ubo2003_directions(), ubo2003_directions(), render,
             [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
               writer.write(l, v, image, size, size);
             });
  writer.finish();
}

// In the child: load, analyze, write; prints the stage table.
int analyze_child(const fs::path& btf, const fs::path& material_path, const std::string& label) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(btf, {}, warnings);
  const double load_seconds = seconds_since(start);
  const std::size_t load_rss = peak_rss_bytes();
  AnalysisOptions options;
  options.progress = false;
  const AnalysisResult result = analyze_btf(dataset, options);
  const auto write_start = std::chrono::steady_clock::now();
  check(write_material_file(material_path.string(), result.material), "cannot write the material");
  const double write_seconds = seconds_since(write_start);
  const double raw =
      static_cast<double>(dataset.present_pairs().size()) * static_cast<double>(dataset.pixel_count()) * 3.0;
  const auto bytes = static_cast<double>(fs::file_size(material_path));
  std::printf("%s: raw 8-bit data %.1f MiB\n", label.c_str(), raw / 1048576.0);
  std::printf("  %-24s %9s %14s\n", "stage", "seconds", "peak RSS MiB");
  std::printf("  %-24s %9.2f %14.0f\n", "load JPEGs", load_seconds, load_rss / 1048576.0);
  for (const StageReport& s : result.stages)
    std::printf("  %-24s %9.2f %14.0f\n", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
  std::printf("  %-24s %9.2f %14.0f\n", "write material", write_seconds, peak_rss_bytes() / 1048576.0);
  std::printf("  %-24s %9.2f %14.0f\n", "total", seconds_since(start), peak_rss_bytes() / 1048576.0);
  std::printf("  material file %.1f KiB, compression ratio 1 : %.0f\n\n", bytes / 1024.0, raw / bytes);
  return 0;
}

void run_analyze_bench(const AnalyzeBenchOptions& options) {
  OwnedFolder out(options.out);
  if (options.keep) out.keep();
  const std::vector<std::string> materials =
      options.materials.empty() ? sample_material_names() : options.materials;
  for (const std::string& material : materials) {
    for (std::uint32_t size : options.sizes) {
      const std::string label =
          material + " " + std::to_string(size) + "x" + std::to_string(size) + ", 81 x 81 JPEGs";
      const std::string stem = material + "_" + std::to_string(size);
      const fs::path btf = out.claim(stem);
      const fs::path material_path = out.claim(stem + ".cbtf");
      const auto render_start = std::chrono::steady_clock::now();
      render_jpeg_btf(material, size, btf);
      std::fprintf(stderr, "rendered %s in %.1f s (not part of the analysis)\n", label.c_str(),
                   seconds_since(render_start));
      std::fflush(stdout);
      std::fflush(stderr);
      const pid_t child = fork();
      if (child < 0) throw CommandError("cannot start the analysis process");
      if (child == 0) {
        int status = 1;
        try {
          status = analyze_child(btf, material_path, label);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "carbtf: error: %s\n", e.what());
        }
        std::fflush(stdout);
        _exit(status);
      }
      int status = 0;
      waitpid(child, &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw CommandError("the analysis of " + label + " failed");
      if (!options.keep) out.release(btf);
    }
  }
}

}  // namespace

void register_bench_analyze_command(CLI::App& bench) {
  auto options = std::make_shared<AnalyzeBenchOptions>();
  auto* command =
      bench.add_subcommand("analyze",
                           "Analysis time and peak RSS per stage, file size and compression ratio, for each "
                           "sample material rendered as 81x81 JPEGs");
  command->add_option("--materials", options->materials, "Sample materials (default: all)");
  command->add_option("--sizes", options->sizes, "Image sizes")
      ->check(CLI::Range(16u, 1024u))
      ->capture_default_str();
  command
      ->add_option("--out", options->out,
                   "Folder for the rendered sets and materials (created if missing; only what the bench "
                   "creates there is removed)")
      ->capture_default_str();
  command->add_flag("--keep", options->keep, "Keep the rendered images and the material files");
  command->callback([options] { run_analyze_bench(*options); });
}

}  // namespace carbtf::cli
