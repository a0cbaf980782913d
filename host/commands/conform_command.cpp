// `carbtf conform [material.cbtf]`: headless GPU-vs-CPU conformance of subspace synthesis. Runs the
// Vulkan pipeline and the CPU float32 reference on the same material, seed and size, compares every
// stage pixel by pixel, checks block-wise synthesis against the whole, reports float32 against float64,
// and exits non-zero beyond the tolerance.
#include <cstdio>

#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/reference/conformance_procedure.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {
namespace {

struct ConformOptions {
  DeviceOptions device;
  std::string material;
  std::uint32_t size = 512;
  reference::ConformanceSettings settings;
  double tolerance = 1e-5;
  bool extremes = true;
  std::uint32_t large_size = 4096;
  std::vector<std::uint32_t> growth_sizes = {256, 512, 1024, 2048, 4096};
};

void print_case(const reference::CaseConformance& r, double tolerance) {
  std::printf("\n%s: GPU %.1f ms, CPU float32 reference %.1f ms (1 thread)\n", r.name.c_str(),
              r.implementation_ms, r.reference_ms);
  std::printf("  %-14s %6s %14s %14s %10s %8s\n", "stage", "items", "max err/std", "RMS err/std", "identical",
              "verdict");
  for (const reference::StageConformance& s : r.stages) {
    std::printf("  %-14s %6u %14.3e %14.3e %10s %8s\n", s.stage.c_str(), s.items, s.error.max_relative,
                s.error.rms_relative, s.identical ? "bits" : "no", s.error.within(tolerance) ? "ok" : "FAIL");
  }
  std::printf("  float32 (GPU) against the float64 reference: max %.3e, RMS %.3e of the std\n",
              r.float32_vs_float64.max_relative, r.float32_vs_float64.rms_relative);
}

void run_conform(const ConformOptions& options) {
  auto context = make_context(options.device);
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
  reference::SynthesisAdapter<SubspaceSynthesizer> gpu(*synthesizer);
  std::printf(
      "conformance on %s: GPU against the CPU float32 reference, seed %llu, margin %u; tolerance %.1e of "
      "each band's std (max abs error)\n",
      context->device_info().name.c_str(), static_cast<unsigned long long>(options.settings.seed),
      options.settings.margin, options.tolerance);
  std::vector<reference::ConformanceCase> cases;
  if (!options.material.empty()) {
    Material material;
    check(read_material_file(options.material, material), "cannot read the material");
    const std::string size = std::to_string(options.size);
    cases.push_back({options.material + " at " + size + "x" + size, std::move(material), options.size});
  }
  if (options.extremes) {
    for (auto& extreme : reference::extreme_conformance_cases(options.large_size))
      cases.push_back(std::move(extreme));
  }
  std::uint32_t failures = 0;
  for (const reference::ConformanceCase& c : cases) {
    std::printf("running %s...\n", c.name.c_str());
    std::fflush(stdout);
    const reference::CaseConformance report = reference::run_conformance_case(c, options.settings, gpu);
    print_case(report, options.tolerance);
    std::fflush(stdout);
    failures += report.failures(options.tolerance);
  }
  if (options.extremes) {
    std::printf(
        "\nfloat32 error growth with field size, near-unit-root band, against float64 (GPU = CPU float32 "
        "where the stages above say bits):\n"
        "  %8s %14s %14s %10s\n",
        "size", "max err/std", "RMS err/std", "GPU bits");
    reference::float32_growth(
        options.growth_sizes, options.settings, gpu, [](const reference::GrowthRow& row) {
          std::printf("  %8u %14.3e %14.3e %10s\n", row.size, row.float32_vs_float64.max_relative,
                      row.float32_vs_float64.rms_relative, row.implementation_bits ? "yes" : "NO");
          std::fflush(stdout);
        });
  }
  check_validation(*context);
  if (failures > 0) {
    throw CommandError(std::to_string(failures) + " stage comparison(s) beyond the tolerance of " +
                       std::to_string(options.tolerance) + " of the std");
  }
  std::printf("\nall stages within %.1e of the std\n", options.tolerance);
}

}  // namespace

void register_conform_command(CLI::App& app) {
  auto options = std::make_shared<ConformOptions>();
  auto* command = app.add_subcommand(
      "conform",
      "Headless GPU-vs-CPU conformance of synthesis: every stage (noise, band fields, collapse, colour, "
      "interpolation) compared pixel by pixel, 2x2 blocks from stored initialization values against the "
      "whole, stiff and extreme cases, float32 error growth against float64; "
      "exits non-zero beyond the tolerance");
  command->add_option("material", options->material,
                      "Material file (.cbtf); without one only the built-in extreme cases run");
  command->add_option("--size", options->size, "Output size for the material")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command->add_option("--seed", options->settings.seed, "Seed")->check(non_negative())->capture_default_str();
  command
      ->add_option("--margin", options->settings.margin,
                   "The most CAR burn-in rows and columns a band gets (each takes what its stability needs, "
                   "docs/design.md 4.4)")
      ->check(CLI::Range(0u, 4096u))
      ->capture_default_str();
  command
      ->add_option(
          "--tolerance", options->tolerance,
          "Largest accepted max abs error, relative to each band's or channel's std (both sides follow one "
          "operation order, so the expected error is 0)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_flag("!--no-extremes", options->extremes, "Skip the built-in stiff and extreme cases");
  command->add_option("--large-size", options->large_size, "Size of the large extreme case")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command->add_option("--growth-sizes", options->growth_sizes, "Sizes of the float32 error-growth study")
      ->delimiter(',')
      ->check(CLI::Range(1u, 16384u));
  add_car_scheme_option(*command, options->settings.scheme);
  add_device_options(*command, options->device);
  command->callback([options] { run_conform(*options); });
}

}  // namespace carbtf::cli
