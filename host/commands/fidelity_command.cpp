// `carbtf fidelity material.cbtf DATASET --out DIR`: how close the model looks to the measurement it
// was fitted to, measured (docs/design.md 5): both drawn through the same render pass at a spread of measured
// (light, view) pairs, compared by the calibrated texture measure on distributions, beside the best
// stationary Gaussian texture. Prints rel per pair, mean and worst; writes a CSV, a markdown table, a
// CSV per octave (where a distance comes from) and a picture grid (measured | model | Gaussian reference).
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "fidelity/fidelity_run.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct FidelityOptions {
  DeviceOptions device;
  std::string material;
  std::string dataset;
  std::string out = "carbtf-fidelity";
  std::uint64_t seed = 1;
  std::vector<std::uint32_t> pairs;  // light, view, light, view, ... (indices); empty: the default spread
  std::size_t spread = 0;            // > 0: this many pairs spread over every light and view instead
};

void run_fidelity_command(const FidelityOptions& options) {
  Material material;
  check(read_material_file(options.material, material), "cannot read the material");
  if (options.pairs.size() % 2 != 0)
    throw CommandError("--pairs: give LIGHT,VIEW index pairs (an even count)");
  std::vector<FidelityPair> pairs;
  for (std::size_t i = 0; i < options.pairs.size(); i += 2) {
    if (options.pairs[i] >= material.lights.size() || options.pairs[i + 1] >= material.views.size()) {
      throw CommandError("--pairs: (" + std::to_string(options.pairs[i]) + ", " +
                         std::to_string(options.pairs[i + 1]) + ") is outside the " +
                         std::to_string(material.lights.size()) + " lights x " +
                         std::to_string(material.views.size()) + " views of " + options.material);
    }
    pairs.push_back(
        {options.pairs[i], options.pairs[i + 1],
         "light " + std::to_string(options.pairs[i]) + " view " + std::to_string(options.pairs[i + 1])});
  }
  const BtfDataset dataset = load_measurement_of(material, options.dataset, "DATASET");
  if (options.spread > 0) {
    pairs = spread_fidelity_pairs(material, dataset, options.spread);
    if (pairs.empty())
      throw CommandError("--spread: no measured pair of " + options.dataset +
                         " can be scored (its images are too small)");
  }
  if (pairs.empty()) pairs = default_fidelity_pairs(material);
  const fs::path out = options.out;
  create_folder(out);
  auto context = make_context(options.device);
  std::printf(
      "fidelity of %s against %s: %zu pairs, %ux%u, on %s (s: 0 = as close as the measurement to itself, 1 = "
      "no better than "
      "a Gaussian field with its spectrum; rel: 1 = white noise)\n",
      options.material.c_str(), options.dataset.c_str(), pairs.size(), dataset.width(), dataset.height(),
      context->device_info().name.c_str());
  std::fflush(stdout);
  FidelityRunOptions run;
  run.seed = options.seed;
  const std::vector<PairFidelity> results = run_fidelity(*context, material, dataset, pairs, run);
  check_validation(*context);
  const FidelitySummaryLine summary = summarize(results);
  std::printf("%s\n", summary_text(summary).c_str());

  write_output_file(out / "fidelity.csv", fidelity_csv(results, material));
  write_output_file(out / "fidelity.md", fidelity_markdown(results));
  write_output_file(out / "fidelity_octaves.csv", fidelity_octaves_csv(results));
  const RgbField grid = fidelity_grid(results);
  write_rgb_image(out / "fidelity_grid.png", grid.rgb, grid.width, grid.height);
  std::printf(
      "wrote %s/fidelity.csv, fidelity.md, fidelity_octaves.csv (per octave: L*, a*, b* energies and light "
      "vectors) and "
      "fidelity_grid.png (rows: pairs; columns: measured | model | Gaussian reference)\n",
      out.string().c_str());
}

}  // namespace

void register_fidelity_command(CLI::App& app) {
  auto options = std::make_shared<FidelityOptions>();
  auto* command =
      app.add_subcommand("fidelity",
                         "How close the model looks to its measurement: model and measured "
                         "images through the same render pass at a spread of "
                         "(light, view) pairs, grazing light included, scored by a calibrated "
                         "texture measure on distributions (s: 0 = the measurement "
                         "against another region of itself, 1 = no better than a Gaussian field "
                         "of its spectrum; rel: 1 = white noise), "
                         "with a verdict against that Gaussian per pair; CSV, markdown, a CSV "
                         "per octave (L*, a*, b* energies and light vectors of model and measurement) and a "
                         "picture grid (measured | model | Gaussian)");
  command->add_option("material", options->material, "Material file (.cbtf)")->required();
  command->add_option("dataset", options->dataset, "The measured BTF the material was analysed from")
      ->required();
  command->add_option("--out", options->out, "Output folder")->capture_default_str();
  command->add_option("--seed", options->seed, "Seed of the synthesis and of the reference noise")
      ->capture_default_str();
  command
      ->add_option("--pairs", options->pairs,
                   "LIGHT,VIEW index pairs to score instead of the default spread (top view at 15, 45, "
                   "75 degree light; views at 45 and 60 degrees)")
      ->delimiter(',');
  command
      ->add_option("--spread", options->spread,
                   "Score this many pairs spread evenly over every measured light and view instead of the "
                   "default five "
                   "(the same pairs on every run): a broader verdict, which no single pair sways; 16 takes "
                   "about three "
                   "times as long")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1024}))
      ->excludes("--pairs");
  add_device_options(*command, options->device);
  command->callback([options] { run_fidelity_command(*options); });
}

}  // namespace carbtf::cli
