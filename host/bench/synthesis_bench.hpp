// The measurements of `carbtf bench synth`: error against run time of subspace-image synthesis. Each
// case synthesizes on the Vulkan device (median of timed runs after a warm-up, per stage) and on the
// CPU references (float32 timed, float64 the accuracy reference), and optionally scores fidelity
// against the measured images. Nothing here asserts a timing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "carbtf/analysis/quality/subspace_fidelity.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/reference/conformance.hpp"

namespace carbtf::cli {

struct SynthesisBenchSettings {
  std::uint32_t margin = 64;
  unsigned repeats = 5;
  unsigned cpu_threads = 2;
  CarScheme scheme = CarScheme::automatic;
  bool skip_cpu = false;  // skip the float32 CPU timing (the float64 reference still runs)
};

struct SynthesisBenchCase {
  std::string sweep;
  std::uint32_t size = 512;
  std::uint32_t levels = 3;
  std::uint32_t neighbours = 0;  // 0: the material's own / mixed shapes
  std::uint32_t subspaces = 20;
};

struct SynthesisBenchRow {
  SynthesisBenchCase config;
  std::string scheme;
  double gpu_ms = 0.0;           // median GPU timestamps, whole synthesis
  double gpu_prepare_ms = 0.0;   // of which the frames (car_prepare),
  double gpu_car_ms = 0.0;       // the recursions with their noise,
  double gpu_collapse_ms = 0.0;  // the pyramid collapse
  double gpu_colour_ms = 0.0;    // and the colour transform
  double gpu_wall_ms = 0.0;      // median wall time including submit, wait and readback
  double cpu_ms = 0.0;           // CPU float32 reference on cpu_threads threads
  double cpu64_ms = 0.0;         // CPU float64 reference (the accuracy reference)
  reference::ConformanceError gpu_error;
  reference::ConformanceError cpu_error;
  SubspaceFidelity fidelity;  // of the GPU images against the measured pairs they represent (pairs 0: none)
  std::uint32_t batches = 0;
  std::uint32_t dispatches = 0;
};

// One case: the first `c.subspaces` of `loaded` (the whole material, so that its index table stays
// valid), or a synthetic material of the case's shape when `loaded` is null. `measured` (may be null):
// representative_images() of the loaded material, for the fidelity column.
SynthesisBenchRow run_synthesis_case(const SynthesisBenchSettings& settings, const SynthesisBenchCase& c,
                                     SubspaceSynthesizer& synthesizer, const Material* loaded,
                                     const std::vector<RgbField>* measured);

// "mixed" for 0, else the count.
std::string neighbours_text(std::uint32_t n);

// bench_synth.csv, bench_synth.md and bench_synth.png (error against run time) under `out`, and with
// fidelity figures bench_synth_fidelity.png (mean rel against run time).
void write_synthesis_bench_report(const std::filesystem::path& out,
                                  const std::vector<SynthesisBenchRow>& rows, const std::string& device,
                                  unsigned cpu_threads, bool with_fidelity);

}  // namespace carbtf::cli
