// The demo's HTML report (index.html beside the pictures `carbtf demo` writes): the material on a
// sphere, the fidelity grid with its figures, the analysis pictures, measured and synthesized subspace
// images, and the demo's figures and stage times.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "fidelity/fidelity_run.hpp"

namespace carbtf::cli {

struct DemoFigures {
  std::string material;  // the sample's name
  std::uint32_t sample_size = 0;
  std::uint32_t texture_size = 0;
  std::size_t subspaces = 0;
  std::size_t measured_images = 0;
  std::string device;  // name (type)
  double raw_bytes = 0.0, file_bytes = 0.0;
  std::size_t identical_values = 0, values = 0;  // GPU against the CPU reference
  double gpu_synthesis_ms = 0.0;
  std::vector<std::pair<std::string, double>> stage_times;  // stage, seconds
};

// Throws CommandError when the report cannot be written.
void write_demo_report(const std::filesystem::path& folder, const DemoFigures& f,
                       const std::vector<PairFidelity>& fidelity);

}  // namespace carbtf::cli
