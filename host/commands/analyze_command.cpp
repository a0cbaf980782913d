// `carbtf analyze DATASET --out material.cbtf`: fit the compact model to a measured BTF.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/report/figures.hpp"
#include "carbtf/analysis/resource_usage.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/material/range_tiles.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "report/analysis_report.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct AnalyzeCommandOptions {
  std::string dataset;
  std::string out;
  std::string report;
  AnalysisOptions analysis;
};

void run_analyze(const AnalyzeCommandOptions& options) {
  check_output_file_path(options.out, "--out");
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(options.dataset, {}, warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const double load_seconds = seconds_since(start);
  std::fprintf(stderr, "loaded %zu images of %ux%u in %.2f s\n", dataset.present_pairs().size(),
               dataset.width(), dataset.height(), load_seconds);
  const AnalysisResult result = analyze_btf(
      dataset, options.analysis, [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  // A folder named in --out that is not there yet is made, as the image outputs and --report do; only
  // after the analysis, so that a failed one leaves nothing behind.
  create_folder(fs::path(options.out).parent_path());
  check(write_material_file(options.out, result.material), "cannot write the material");
  if (!options.report.empty()) write_analysis_report(options.report, dataset, result);

  const double raw_bytes =
      static_cast<double>(dataset.present_pairs().size()) * static_cast<double>(dataset.pixel_count()) * 3.0;
  const auto file_bytes = static_cast<double>(fs::file_size(options.out));
  std::printf("%-22s %8s %14s\n", "stage", "seconds", "peak RSS MiB");
  std::printf("%-22s %8.2f %14.0f\n", "load", load_seconds, 0.0);
  for (const StageReport& s : result.stages)
    std::printf("%-22s %8.2f %14.0f\n", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
  std::printf("%-22s %8.2f %14.0f\n", "total", seconds_since(start), peak_rss_bytes() / 1048576.0);
  std::printf("material: %s, %.1f KiB (%u subspaces); raw 8-bit data %.1f MiB; ratio 1 : %.0f\n",
              options.out.c_str(), file_bytes / 1024.0,
              static_cast<unsigned>(result.material.subspaces.size()), raw_bytes / 1048576.0,
              raw_bytes / file_bytes);
  if (!options.report.empty()) std::printf("report: %s\n", options.report.c_str());
}

}  // namespace

void register_analyze_command(CLI::App& app) {
  auto options = std::make_shared<AnalyzeCommandOptions>();
  auto* command = app.add_subcommand(
      "analyze",
      "Fit the compact BTF model (segmentation, range map, colour PCA, pyramid, CAR per band) "
      "and write a .cbtf material file");
  command
      ->add_option("dataset", options->dataset,
                   "A UBO2003 folder or .zip, a manifest .csv, a photometric-stereo folder, or a Bonn "
                   "UBO2014 .btf file (DFMF or raw)")
      ->required();
  command->add_option("--out", options->out, "Material file to write (.cbtf; its folder is made if missing)")
      ->required();
  command->add_option("--report", options->report,
                      "Folder for the pictures and data: index_table.png, eigenvalues.png/.csv, subspace "
                      "images, normals, range map, "
                      "stage times, analysis log");
  AnalysisOptions& a = options->analysis;
  command->add_option("--subspaces,-k", a.segmentation.clusters, "Number of subspaces K (K-means clusters)")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  command->add_option("--bins", a.segmentation.bins, "Bins per Lab channel of the segmentation feature")
      ->check(CLI::Range(2, 1024))
      ->capture_default_str();
  command->add_option("--seed", a.segmentation.seed, "Seed of k-means++ and of the range tiles")
      ->check(non_negative())
      ->capture_default_str();
  command
      ->add_option("--levels", a.pyramid_levels, "Gaussian-Laplacian pyramid levels (the paper uses up to 3)")
      ->check(CLI::Range(1, 6))
      ->capture_default_str();
  command
      ->add_option("--stereo-view", a.stereo_view,
                   "View index for photometric stereo (-1: the view nearest the normal)")
      ->check(CLI::Range(-1, 4095))
      ->capture_default_str();
  command->add_option("--tile-size", a.tiles.tile_size, "Range-map tile size in texels (even)")
      ->check(CLI::Range(4, 1024))
      ->capture_default_str();
  command
      ->add_option("--edge-colours", a.tiles.edge_colours,
                   "Range-tile edge colours per direction: 2 patches each, tiles = colours^4 (more: less "
                   "repetition on large surfaces, a larger file)")
      ->check(CLI::Range(1u, kMaxEdgeColours))
      ->capture_default_str();
  command
      ->add_option("--height-bits", a.tiles.height_bits,
                   "Range-map height quantization in bits (fewer: a smaller file, coarser slopes)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  command
      ->add_option(
          "--tone-bits", a.tiles.tone_bits,
          "Relief-tone quantization in bits, of a grey tone (a tone of R, G and B planes takes 6 bits, "
          "which keep its rounding out of the colour)")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  command->add_flag(
      "!--no-relief-tone", a.relief_tone,
      "For comparison: leave out the relief tone, the photometric-stereo albedo stored with the range tiles "
      "that puts the creases' dark colour where the range map puts the creases. Without it the samples' "
      "models are no nearer than a Gaussian field (docs/figures.md, variant tiles128)");
  command->add_flag_callback(
      "--specular", [&a] { a.relief_specular = AutoChoice::always; },
      "Opt-in: keep the relief's specular lobe wherever it is fitted (highlights where the range map's "
      "facets turn to the half vector of light and view). By default it is kept only where the subspace "
      "models look nearer the measurement with it: the three built-in samples keep it at 256^2, so forcing "
      "it changes their files in nothing; where it was left out, forcing it made coast_sand_rocks look "
      "further (docs/design.md 5.2)");
  command->add_flag(
      "!--no-pair-gains", a.pair_gains,
      "For comparison: leave out the pair gains, per measured light and view the colour gains that give the "
      "pair its measured mean colour, which its subspace image (the representative pair's) does not have. "
      "Without them the file is smaller and coast_sand_rocks looks further (docs/figures.md, variant "
      "no_pair_gains)");
  command->add_option("--threads", a.threads, "Worker threads (0: all cores; at most 256)")
      ->check(CLI::Range(0u, 256u))
      ->capture_default_str();
  command->callback([options] { run_analyze(*options); });
}

}  // namespace carbtf::cli
