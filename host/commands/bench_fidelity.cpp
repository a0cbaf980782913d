// `carbtf bench fidelity DATASET`: error against size (issue 13 item 4), the companion of `bench synth`'s
// error against run time. The dataset is analysed once per model option (the paper's model, larger
// range tiles, the relief tone and its remainder clamp, fewer height bits, the collapse calibration,
// de-shading), each material is scored by the calibrated fidelity measure through the render pass, and
// its file size is set beside the score: a table on stdout, a CSV and a plot of rel against KiB.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/report/figures.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "cli/cli_support.hpp"
#include "cli/owned_folder.hpp"
#include "commands/commands.hpp"
#include "fidelity/fidelity_run.hpp"
#include "fidelity/model_variants.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct FidelityBenchOptions {
  DeviceOptions device;
  std::string dataset;
  std::vector<std::string> variants;  // empty: all
  std::string out = "carbtf-bench-fidelity";
  std::uint64_t seed = 1;
};

struct VariantResult {
  const ModelVariant* variant = nullptr;
  std::uintmax_t bytes = 0;
  double analysis_seconds = 0.0;
  FidelitySummaryLine summary;
};

void run_fidelity_bench(const FidelityBenchOptions& options) {
  std::vector<const ModelVariant*> chosen;
  for (const ModelVariant& v : model_variants()) {
    if (options.variants.empty() ||
        std::find(options.variants.begin(), options.variants.end(), v.name) != options.variants.end()) {
      chosen.push_back(&v);
    }
  }
  for (const std::string& name : options.variants) {
    if (std::none_of(model_variants().begin(), model_variants().end(),
                     [&](const ModelVariant& v) { return name == v.name; })) {
      std::string known;
      for (const ModelVariant& v : model_variants()) known += std::string(known.empty() ? "" : ", ") + v.name;
      throw CommandError("--variants: unknown variant '" + name + "' (known: " + known + ")");
    }
  }
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(options.dataset, {}, warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  OwnedFolder out(options.out);
  out.keep();  // the materials, CSV and plot are the bench's output
  auto context = make_context(options.device);
  std::printf(
      "fidelity against size for %s (%ux%u) on %s; s: 0 = as close as the measurement to itself, 1 = no "
      "better than a "
      "Gaussian field (rel: 1 = white noise)\n",
      options.dataset.c_str(), dataset.width(), dataset.height(), context->device_info().name.c_str());
  std::vector<VariantResult> results;
  for (const ModelVariant* variant : chosen) {
    AnalysisOptions analysis;
    analysis.progress = false;
    analysis.segmentation.seed = options.seed;
    variant->apply(analysis);
    std::fprintf(stderr, "%s: analysing (%s)\n", variant->name, variant->description);
    const auto start = std::chrono::steady_clock::now();
    const AnalysisResult analysed = analyze_btf(dataset, analysis);
    VariantResult r;
    r.variant = variant;
    r.analysis_seconds = seconds_since(start);
    const fs::path path = out.claim(std::string(variant->name) + ".cbtf");
    check(write_material_file(path.string(), analysed.material), "cannot write the material");
    r.bytes = fs::file_size(path);
    FidelityRunOptions run;
    run.seed = options.seed;
    run.progress = false;
    const std::vector<PairFidelity> scored =
        run_fidelity(*context, analysed.material, dataset, default_fidelity_pairs(analysed.material), run);
    check_validation(*context);
    r.summary = summarize(scored);
    std::printf(
        "  %-13s %8.1f KiB  s mean %.3f worst %.3f  rel mean %.3f  beats the Gaussian reference on %zu of "
        "%zu  (analysis %.1f s)\n",
        variant->name, static_cast<double>(r.bytes) / 1024.0, r.summary.mean_structure,
        r.summary.worst_structure, r.summary.mean_rel, r.summary.beats_gaussian, r.summary.pairs,
        r.analysis_seconds);
    std::fflush(stdout);
    results.push_back(r);
  }
  if (!results.empty())
    std::printf("Gaussian reference rel mean %.3f\n", results.front().summary.mean_gaussian_rel);

  const fs::path csv_path = out.claim("fidelity_size.csv");
  std::ostringstream csv;
  csv << "variant,description,bytes,mean_s,worst_s,mean_rel,worst_rel,gaussian_mean_rel,beats_gaussian,pairs,"
         "analysis_seconds\n";
  std::vector<ScatterPoint> points;
  std::vector<std::string_view> legend;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const VariantResult& r = results[i];
    csv << r.variant->name << ",\"" << r.variant->description << "\"," << r.bytes << ","
        << r.summary.mean_structure << "," << r.summary.worst_structure << "," << r.summary.mean_rel << ","
        << r.summary.worst_rel << "," << r.summary.mean_gaussian_rel << "," << r.summary.beats_gaussian << ","
        << r.summary.pairs << "," << r.analysis_seconds << "\n";
    points.push_back(
        {static_cast<double>(r.bytes) / 1024.0, r.summary.mean_structure, static_cast<std::uint32_t>(i)});
    legend.push_back(r.variant->name);
  }
  write_output_file(csv_path, csv.str());
  // The same table as Markdown, for docs/figures.md (scripts/figures.sh): the one place measured
  // figures live, so that no help text or document carries a copy that goes stale.
  std::ostringstream md;
  md << "### " << fs::path(options.dataset).parent_path().filename().string() << "/"
     << fs::path(options.dataset).filename().string() << " (" << dataset.width() << "x" << dataset.height()
     << "), seed " << options.seed << ", " << context->device_info().name << "\n\n"
     << "| variant | KiB | mean s | worst s | mean rel | beats the Gaussian | analysis s |\n"
     << "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const VariantResult& r : results) {
    char row[256];
    std::snprintf(row, sizeof row, "| %s | %.1f | %.3f | %.3f | %.3f | %zu of %zu | %.0f |\n",
                  r.variant->name, static_cast<double>(r.bytes) / 1024.0, r.summary.mean_structure,
                  r.summary.worst_structure, r.summary.mean_rel, r.summary.beats_gaussian, r.summary.pairs,
                  r.analysis_seconds);
    md << row;
  }
  write_output_file(out.claim("fidelity_size.md"), md.str());
  const Figure plot =
      scatter_figure(points, "MATERIAL SIZE (KIB)", "MEAN S (0 = MEASUREMENT, 1 = GAUSSIAN FIELD)", legend);
  write_rgb_image(out.claim("fidelity_size.png"), plot.rgb, plot.width, plot.height, false);
  std::printf(
      "wrote %s: one .cbtf per variant, fidelity_size.csv, fidelity_size.md and fidelity_size.png (mean s "
      "against "
      "size)\n",
      options.out.c_str());
}

}  // namespace

void register_bench_fidelity_command(CLI::App& bench) {
  auto options = std::make_shared<FidelityBenchOptions>();
  auto* command = bench.add_subcommand("fidelity",
                                       "Error against size: the dataset analysed once per model option, each "
                                       "material scored by the calibrated "
                                       "fidelity measure through the render pass (as `carbtf fidelity`), "
                                       "beside its file size; table, CSV and plot");
  command
      ->add_option("dataset", options->dataset,
                   "A measured BTF (UBO2003 folder or zip, a manifest, or a UBO2014 .btf file)")
      ->required();
  std::string names;
  for (const ModelVariant& v : model_variants()) names += std::string("\n  ") + v.name + ": " + v.description;
  command->add_option("--variants", options->variants, "Model variants to compare (default: all):" + names)
      ->delimiter(',');
  command
      ->add_option(
          "--out", options->out,
          "Folder for the materials, CSV, Markdown table and plot (created if missing; existing files "
          "there are refused, not overwritten)")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed of the analysis, the synthesis and the reference noise")
      ->capture_default_str();
  add_device_options(*command, options->device);
  command->callback([options] { run_fidelity_bench(*options); });
}

}  // namespace carbtf::cli
