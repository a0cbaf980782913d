#include "bench/synthesis_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string_view>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/report/figures.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "carbtf/reference/synthetic_material.hpp"
#include "cli/cli_support.hpp"

namespace carbtf::cli {
namespace {

// The material of a case and the subspaces to synthesize: the first `c.subspaces` of the loaded material
// (the whole material, so that its index table stays valid), or a synthetic one with the case's shape.
Material material_for(const SynthesisBenchCase& c, const Material* loaded,
                      std::vector<std::uint32_t>& subspaces) {
  subspaces.clear();
  if (!loaded) return synthetic_material(c.subspaces, c.levels, 3, c.neighbours);
  const auto count = static_cast<std::uint32_t>(std::min<std::size_t>(loaded->subspaces.size(), c.subspaces));
  for (std::uint32_t s = 0; s < count; ++s) subspaces.push_back(s);
  return *loaded;
}

void write_tables(const std::filesystem::path& out, const std::vector<SynthesisBenchRow>& rows,
                  const std::string& device, unsigned threads) {
  std::ostringstream csv;
  csv << "sweep,size,levels,neighbours,subspaces,scheme,batches,dispatches,gpu_ms,gpu_prepare_ms,gpu_car_ms,"
         "gpu_collapse_ms,gpu_colour_ms,gpu_wall_ms,cpu_f32_ms,cpu_f64_ms,"
         "gpu_max_err_over_std,gpu_rms_err_over_std,cpu_f32_max_err_over_std,cpu_f32_rms_err_over_std,"
         "fidelity_pairs,rel_mean,rel_worst,gaussian_rel_mean\n";
  std::ostringstream md;
  md << "# carbtf bench synth\n\nDevice: " << device << ". CPU reference on " << threads
     << " threads. Errors are against the float64 CPU reference, relative to each channel's standard "
        "deviation"
     << ". Fidelity is the calibrated texture measure's rel (docs/design.md 5; 0 = as close as the "
        "measurement "
        "to itself, 1 = white noise) of the GPU images, times the relief tone and the relit range map, "
        "against "
        "the measured image of each subspace's representative pair, mean (worst), beside the best Gaussian "
        "texture's.\n\n"
     << "| sweep | size | levels | neighbours | subspaces | scheme | GPU ms | frames | CAR with noise | "
        "collapse | "
        "colour | GPU wall ms | "
        "CPU f32 ms | CPU f64 ms | GPU max err/std | GPU RMS err/std | CPU f32 max err/std | pairs | rel | "
        "Gaussian rel |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SynthesisBenchRow& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s,%u,%u,%s,%u,%s,%u,%u,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3e,%.3e,%.3e,%.3e\n",
                  r.config.sweep.c_str(), r.config.size, r.config.levels,
                  neighbours_text(r.config.neighbours).c_str(), r.config.subspaces, r.scheme.c_str(),
                  r.batches, r.dispatches, r.gpu_ms, r.gpu_prepare_ms, r.gpu_car_ms, r.gpu_collapse_ms,
                  r.gpu_colour_ms, r.gpu_wall_ms, r.cpu_ms, r.cpu64_ms, r.gpu_error.max_relative,
                  r.gpu_error.rms_relative, r.cpu_error.max_relative, r.cpu_error.rms_relative);
    csv << std::string(line, std::strlen(line) - 1);  // the fidelity columns follow
    const SubspaceFidelity& f = r.fidelity;
    std::snprintf(line, sizeof line, ",%u,%.4f,%.4f,%.4f\n", f.pairs, f.mean_rel, f.worst_rel,
                  f.mean_gaussian_rel);
    csv << line;
    std::snprintf(line, sizeof line,
                  "| %s | %u | %u | %s | %u | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | "
                  "%.2e | %.2e | %.2e |",
                  r.config.sweep.c_str(), r.config.size, r.config.levels,
                  neighbours_text(r.config.neighbours).c_str(), r.config.subspaces, r.scheme.c_str(),
                  r.gpu_ms, r.gpu_prepare_ms, r.gpu_car_ms, r.gpu_collapse_ms, r.gpu_colour_ms, r.gpu_wall_ms,
                  r.cpu_ms, r.cpu64_ms, r.gpu_error.max_relative, r.gpu_error.rms_relative,
                  r.cpu_error.max_relative);
    md << line;
    if (f.pairs == 0) {
      md << " - | - | - |\n";
    } else {
      std::snprintf(line, sizeof line, " %u | %.3f (%.3f) | %.3f |\n", f.pairs, f.mean_rel, f.worst_rel,
                    f.mean_gaussian_rel);
      md << line;
    }
  }
  write_output_file(out / "bench_synth.csv", csv.str());
  write_output_file(out / "bench_synth.md", md.str());
}

}  // namespace

std::string neighbours_text(std::uint32_t n) {
  return n == 0 ? "mixed" : std::to_string(n);
}

SynthesisBenchRow run_synthesis_case(const SynthesisBenchSettings& options, const SynthesisBenchCase& c,
                                     SubspaceSynthesizer& synthesizer, const Material* loaded,
                                     const std::vector<RgbField>* measured) {
  std::vector<std::uint32_t> subspaces;
  const Material material = material_for(c, loaded, subspaces);
  SynthesisRequest request;
  request.seed = 1;
  request.width = request.height = c.size;
  request.margin = options.margin;
  request.scheme = options.scheme;
  request.subspaces = subspaces;
  SynthesisBenchRow row;
  row.config = c;
  row.config.subspaces =
      static_cast<std::uint32_t>(subspaces.empty() ? material.subspaces.size() : subspaces.size());

  SynthesizedImages images;
  check(synthesizer.synthesize(material, request, images), "synthesis failed");  // warm-up
  std::vector<double> gpu, prepare, car, collapse, colour, wall;
  for (unsigned i = 0; i < options.repeats; ++i) {
    SynthesisTiming timing;
    const auto start = std::chrono::steady_clock::now();
    check(synthesizer.synthesize(material, request, images, &timing), "synthesis failed");
    wall.push_back(seconds_since(start) * 1e3);
    gpu.push_back(timing.total_ms);
    prepare.push_back(timing.prepare_ms);
    car.push_back(timing.car_ms);
    collapse.push_back(timing.collapse_ms);
    colour.push_back(timing.colour_ms);
    row.batches = timing.batches;
    row.dispatches = timing.dispatches;
  }
  row.scheme = car_scheme_name(synthesizer.scheme());
  row.gpu_ms = median(gpu);
  row.gpu_prepare_ms = median(prepare);
  row.gpu_car_ms = median(car);
  row.gpu_collapse_ms = median(collapse);
  row.gpu_colour_ms = median(colour);
  row.gpu_wall_ms = median(wall);

  const SynthesisBlock& block = request;
  auto start = std::chrono::steady_clock::now();
  const auto f64 = reference::synthesize_subspaces_f64(material, subspaces, block, options.cpu_threads);
  row.cpu64_ms = seconds_since(start) * 1e3;
  std::vector<std::vector<float>> f32;
  if (!options.skip_cpu) {
    start = std::chrono::steady_clock::now();
    f32 = reference::synthesize_subspaces(material, subspaces, block, options.cpu_threads);
    row.cpu_ms = seconds_since(start) * 1e3;
  }
  for (std::size_t s = 0; s < material.subspaces.size(); ++s) {
    if (images.images[s].empty()) continue;
    const std::uint32_t channels = material.subspaces[s].channels;
    row.gpu_error =
        reference::worst_of(row.gpu_error, reference::conformance_error(images.images[s], f64[s], channels));
    if (!f32.empty()) {
      row.cpu_error =
          reference::worst_of(row.cpu_error, reference::conformance_error(f32[s], f64[s], channels));
    }
  }
  if (measured) row.fidelity = subspace_fidelity(material, images, *measured);
  return row;
}

void write_synthesis_bench_report(const std::filesystem::path& out,
                                  const std::vector<SynthesisBenchRow>& rows, const std::string& device,
                                  unsigned cpu_threads, bool with_fidelity) {
  write_tables(out, rows, device, cpu_threads);
  std::vector<ScatterPoint> points;
  for (const SynthesisBenchRow& r : rows) {
    points.push_back({r.gpu_ms, std::max(r.gpu_error.max_relative, 1e-9), 0});
    if (r.cpu_ms > 0) points.push_back({r.cpu_ms, std::max(r.cpu_error.max_relative, 1e-9), 1});
  }
  const std::string device_entry = "GPU: " + device.substr(0, 40);
  const std::string cpu_entry = "CPU REFERENCE, " + std::to_string(cpu_threads) + " THREADS";
  const std::string_view legend[] = {device_entry, cpu_entry};
  const Figure plot = scatter_figure(points, "RUN TIME (MS)", "MAX ERROR / STD AGAINST FLOAT64", legend);
  write_rgb_image((out / "bench_synth.png").string(), plot.rgb, plot.width, plot.height, false);
  if (with_fidelity) {
    std::vector<ScatterPoint> fidelity;
    for (const SynthesisBenchRow& r : rows) {
      if (r.fidelity.pairs > 0) fidelity.push_back({r.gpu_ms, std::max(r.fidelity.mean_rel, 1e-3), 0});
    }
    const std::string_view fidelity_legend[] = {device_entry};
    const Figure figure =
        scatter_figure(fidelity, "RUN TIME (MS)", "MEAN REL AGAINST THE MEASURED IMAGES", fidelity_legend);
    write_rgb_image((out / "bench_synth_fidelity.png").string(), figure.rgb, figure.width, figure.height,
                    false);
  }
}

}  // namespace carbtf::cli
