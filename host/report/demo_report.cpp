#include "report/demo_report.hpp"

#include <algorithm>
#include <cstdio>

#include "cli/cli_support.hpp"
#include "report/html_report.hpp"
#include "report/pictures.hpp"

namespace carbtf::cli {
namespace {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

}  // namespace

void write_demo_report(const std::filesystem::path& folder, const DemoFigures& f,
                       const std::vector<PairFidelity>& fidelity) {
  const FidelitySummaryLine summary = summarize(fidelity);
  HtmlReport report("carbtf demo: " + f.material);
  report.paragraph(
      "The whole pipeline on built-in data: a sample material rendered as a measured BTF (81 lights x 81 "
      "views), analysed into a material file of a few tens of kilobytes, synthesized on the Vulkan device "
      "at any size, and rendered with parallax bump mapping.");
  report.heading("The material on a sphere");
  report.image("sphere.png",
               "model, " + std::to_string(f.texture_size) + "^2 synthesized texture, two directional lights",
               960);
  report.image(
      "sphere_back.png",
      "the same from behind, where the texture coordinates wrap: the periodic synthesis leaves no seam", 960);
  report.heading("Fidelity: model beside measurement");
  report.paragraph(
      "The model and the measured images drawn through the same render pass (a plane seen orthographically "
      "from "
      "the measured view, lit from the measured light), at a spread of pairs with grazing light. The model "
      "is a "
      "random field: it matches statistics, not pixels, so a calibrated texture measure compares "
      "distributions (Lab marginals, oriented band responses and local energy per octave, and the coherence "
      "of local energy across octaves and orientations that only structure has). The structure score s is 0 "
      "for the measurement against another region of itself and 1 for the third column, the measurement with "
      "random Fourier phases: the same spectrum without a crease, thread or rock, the best any Gaussian "
      "field "
      "can do. Below 1 the model beats it; rel is the same distance with white noise of the same colours at "
      "1.");
  report.image("fidelity_grid.png", "rows: pairs; columns: measured | model | Gaussian reference", 3 * 160);
  std::vector<std::vector<std::string>> fidelity_rows{
      {"pair", "s (model)", "rel (model)", "rel (Gaussian reference)", "model beats it"}};
  for (const PairFidelity& r : fidelity) {
    fidelity_rows.push_back({r.pair.label, format("%.3f", r.result.structure), format("%.3f", r.result.rel),
                             format("%.3f", r.result.gaussian_rel),
                             r.result.beats_gaussian() ? "yes" : "no"});
  }
  fidelity_rows.push_back(
      {"mean (worst)",
       format("%.3f", summary.mean_structure) + " (" + format("%.3f", summary.worst_structure) + ")",
       format("%.3f", summary.mean_rel) + " (" + format("%.3f", summary.worst_rel) + ")",
       format("%.3f", summary.mean_gaussian_rel),
       std::to_string(summary.beats_gaussian) + " of " + std::to_string(summary.pairs)});
  report.table(fidelity_rows);
  report.heading("Analysis");
  report.image_row({{"analysis/index_table.png", "subspace index table (lights x views)"},
                    {"analysis/eigenvalues.png", "eigenvalue spectrum of the segmentation features"}},
                   420);
  std::vector<std::pair<std::string, std::string>> subspaces;
  for (std::size_t s = 0; s < std::min<std::size_t>(f.subspaces, 6); ++s) {
    subspaces.push_back(
        {"analysis/subspace_" + two_digits(s) + ".png", "subspace " + std::to_string(s) + ", measured"});
    subspaces.push_back(
        {"synthesized_" + two_digits(s) + ".png", "subspace " + std::to_string(s) + ", synthesized"});
  }
  report.heading("Subspace images, measured and synthesized");
  report.image_row(subspaces, 160);
  report.heading("Figures");
  report.table(
      {{"figure", "value"},
       {"device", f.device},
       {"measured BTF", std::to_string(f.measured_images) + " images of " + std::to_string(f.sample_size) +
                            "^2, " + format("%.1f MiB as 8-bit RGB", f.raw_bytes / 1048576.0)},
       {"material file",
        format("%.1f KiB", f.file_bytes / 1024.0) + ", " + std::to_string(f.subspaces) + " subspaces"},
       {"compression ratio", "1 : " + format("%.0f", f.raw_bytes / f.file_bytes)},
       {"GPU vs CPU synthesis",
        std::to_string(f.identical_values) + " of " + std::to_string(f.values) + " values bit-identical"},
       {"GPU synthesis time (timestamps)", format("%.1f ms", f.gpu_synthesis_ms)}});
  std::vector<std::vector<std::string>> times{{"stage", "time"}};
  for (const auto& [stage, seconds] : f.stage_times) times.push_back({stage, format("%.2f s", seconds)});
  report.table(times);
  if (std::string error; !report.write(folder, error)) throw CommandError(error);
}

}  // namespace carbtf::cli
