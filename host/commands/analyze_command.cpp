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
  std::fprintf(stderr, "loaded %zu images of %ux%u in %.2f s\n", dataset.present_pairs().size(), dataset.width(), dataset.height(), load_seconds);
  const AnalysisResult result = analyze_btf(dataset, options.analysis, [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  check(write_material_file(options.out, result.material), "cannot write the material");
  if (!options.report.empty()) write_analysis_report(options.report, dataset, result);

  const double raw_bytes = static_cast<double>(dataset.present_pairs().size()) * static_cast<double>(dataset.pixel_count()) * 3.0;
  const auto file_bytes = static_cast<double>(fs::file_size(options.out));
  std::printf("%-22s %8s %14s\n", "stage", "seconds", "peak RSS MiB");
  std::printf("%-22s %8.2f %14.0f\n", "load", load_seconds, 0.0);
  for (const StageReport& s : result.stages) std::printf("%-22s %8.2f %14.0f\n", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
  std::printf("%-22s %8.2f %14.0f\n", "total", seconds_since(start), peak_rss_bytes() / 1048576.0);
  std::printf("material: %s, %.1f KiB (%u subspaces); raw 8-bit data %.1f MiB; ratio 1 : %.0f\n", options.out.c_str(), file_bytes / 1024.0,
              static_cast<unsigned>(result.material.subspaces.size()), raw_bytes / 1048576.0, raw_bytes / file_bytes);
  if (!options.report.empty()) std::printf("report: %s\n", options.report.c_str());
}

// An option taking auto, yes or no into an AutoChoice; its help shows the current value as default.
void add_auto_choice(CLI::App* command, const std::string& name, AutoChoice& target, const std::string& help) {
  static const std::map<std::string, AutoChoice> choices{
      {"auto", AutoChoice::automatic}, {"yes", AutoChoice::always}, {"no", AutoChoice::never}};
  const auto current = std::find_if(choices.begin(), choices.end(), [&](const auto& c) { return c.second == target; });
  command->add_option_function<std::string>(name, [&target](const std::string& value) { target = choices.at(value); }, help)
      ->check(CLI::IsMember({"auto", "yes", "no"}))
      ->default_str(current->first);
}

}  // namespace

void register_analyze_command(CLI::App& app) {
  auto options = std::make_shared<AnalyzeCommandOptions>();
  auto* command = app.add_subcommand("analyze", "Fit the compact BTF model (segmentation, range map, colour PCA, pyramid, CAR per band) "
                                                "and write a .cbtf material file");
  command->add_option("dataset", options->dataset, "A UBO2003 folder or .zip, or a manifest .csv")->required();
  command->add_option("--out", options->out, "Material file to write (.cbtf)")->required();
  command->add_option("--report", options->report,
                      "Folder for the pictures and data: index_table.png, eigenvalues.png/.csv, subspace images, normals, range map, "
                      "stage times, analysis log");
  AnalysisOptions& a = options->analysis;
  command->add_option("--subspaces,-k", a.segmentation.clusters, "Number of subspaces K (K-means clusters)")
      ->check(CLI::Range(1, 20))->capture_default_str();
  command->add_option("--bins", a.segmentation.bins, "Bins per Lab channel of the segmentation feature")
      ->check(CLI::Range(2, 1024))->capture_default_str();
  command->add_option("--seed", a.segmentation.seed, "Seed of k-means++ and of the range tiles")->check(non_negative())->capture_default_str();
  command->add_option("--levels", a.pyramid_levels, "Gaussian-Laplacian pyramid levels (the paper uses up to 3)")->check(CLI::Range(1, 6))->capture_default_str();
  command->add_option("--other-levels", a.other_level_counts,
                      "With the relief tone, pyramid level counts a subspace image may take instead of --levels: per "
                      "subspace, one wins where its model looks at least 2% nearer the measurement (texture "
                      "measure). 2 beside 3 lowers fabric's mean rel at 256^2 from 0.48 to 0.45 and leaves leather's model "
                      "as it was; 0: none, every subspace takes --levels")
      ->check(CLI::Range(0u, 6u))
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--stereo-view", a.stereo_view, "View index for photometric stereo (-1: the view nearest the normal)")
      ->check(CLI::Range(-1, 4095))->capture_default_str();
  command->add_option("--tile-size", a.tiles.tile_size, "Range-map tile size in texels (even)")->check(CLI::Range(4, 1024))->capture_default_str();
  command->add_option("--edge-colours", a.tiles.edge_colours,
                      "Range-tile edge colours per direction: 2 patches each, tiles = colours^4 (more: less repetition on large surfaces, a larger file)")
      ->check(CLI::Range(1u, kMaxEdgeColours))
      ->capture_default_str();
  command->add_option("--height-bits", a.tiles.height_bits, "Range-map height quantization in bits (fewer: a smaller file, coarser slopes)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  command->add_option("--tone-bits", a.tiles.tone_bits, "Relief-tone quantization in bits")->check(CLI::Range(1, 8))->capture_default_str();
  command->add_option("--feather", a.tiles.feather, "Texels over which each range-tile cut cross-fades its two patches (0: hard cuts)")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  command->add_flag("--collapse-calibration", a.calibrate_collapse,
                    "Rescale each band's sigma so that the collapsed pyramid keeps the measured contrast (the synthesized "
                    "images otherwise keep 55-80% of the measured variance)");
  command->add_flag("!--no-relief-tone", a.relief_tone,
                    "Leave out the relief tone: the photometric-stereo albedo stored with the range tiles, which puts the "
                    "creases' dark colour where the range map puts the creases (on by default)");
  command->add_flag("--coloured-tone", a.coloured_tone,
                    "Let each colour channel follow the relief tone by its own measured slope where those slopes explain "
                    "most of how the channels' tones differ (a fabric of blue and white threads; the tone stays grey "
                    "otherwise). Off by default: it can leave the smooth texture's noise too strong on small images");
  add_auto_choice(command, "--tone-planes", a.tone_planes,
                  "Store the relief tone as one plane per colour channel (R, G, B), so that colour follows the relief "
                  "texel by texel (threads of different colours keep their colours): auto where the tone's colour departs "
                  "from grey visibly (a two-colour weave, not a leather), yes, or no. Off by default: fabric looks much "
                  "nearer its measurement with it (mean rel 0.42 -> 0.35 at 256^2), but the measure then no longer sees its "
                  "noise: every sigma halved scores as well (docs/design.md 4.2)");
  add_auto_choice(command, "--shadows", a.relief_shadows,
                  "With the relief tone, let the relief cast shadows in the render pass (a crease wall that faces the "
                  "light stays lit, the crease behind it goes dark): auto at the strength that best explains the "
                  "photometric-stereo view's images, where shadows explain them better (a rocky scan, not a leather); "
                  "yes at full strength; no");
  command->add_option("--remainder-clamp", a.remainder_clamps,
                      "With the relief tone, each subspace image's smooth remainder is clamped to its median +- K robust "
                      "standard deviations before the CAR fit, so that relief lines the tone does not explain do not become "
                      "speckle; per subspace the K of this list whose model looks nearest the measurement (texture "
                      "measure) is kept. One value fixes it; 0: no clamp")
      ->check(CLI::Range(0.0, 100.0))
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--selection-draws", a.selection_draws,
                      "Noise draws each clamp and tone-weight candidate is synthesized from; it scores the mean texture "
                      "distance, so the choice follows the model rather than one draw's noise. The subspace models' analysis "
                      "time grows with it; 3 helped fabric and not leather or coast_sand_rocks")
      ->check(CLI::Range(1u, 16u))
      ->capture_default_str();
  command->add_option("--tone-weights", a.tone_weights,
                      "With the relief tone, the candidate shares of the tone each subspace image takes (0: none, 1: all); "
                      "per subspace the one whose model looks nearest the measurement is kept, with its clamp. 0,1 lowers "
                      "coast_sand_rocks' mean rel on fidelity's five pairs (0.155 -> 0.142 at 256^2) but raises it over 16 "
                      "spread pairs (0.278 -> 0.318 at seed 1); one value fixes it")
      ->check(CLI::Range(0.0, 1.0))
      ->delimiter(',')
      ->capture_default_str();
  command->add_flag("--specular", a.relief_specular,
                    "With the relief tone, add the relief's specular lobe: highlights where the range map's facets turn to "
                    "the half vector of light and view, fitted to the photometric-stereo view's images and kept where they "
                    "explain them better. Off by default: fabric looks nearer its measurement with it (mean rel 0.42 -> 0.39 "
                    "at 256^2, 0.35 -> 0.32 with --tone-planes auto), coast_sand_rocks further on fidelity's default five pairs (0.155 "
                    "-> 0.194) but nearer over 16 spread pairs (fidelity --spread 16: 0.298 -> 0.277)");
  command->add_flag("!--no-pair-gains", a.pair_gains,
                    "Leave out the pair gains: per measured light and view, colour gains that give the pair its measured "
                    "mean colour, which its subspace image (the representative pair's) does not have (on by default)");
  command->add_option("--deshade", a.deshade_floor,
                      "Divide the representative pair's relit range map out of each subspace image before fitting, the factor "
                      "floored at this value (0: off)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--threads", a.threads, "Worker threads (0: all cores; at most 256)")->check(CLI::Range(0u, 256u))->capture_default_str();
  command->callback([options] {
    std::erase(options->analysis.other_level_counts, 0u);  // 0: none
    run_analyze(*options);
  });
}

}  // namespace carbtf::cli
