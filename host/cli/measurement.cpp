#include "cli/measurement.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "cli/cli_support.hpp"

namespace carbtf::cli {

namespace {

// Within 1e-4 rad; the azimuth modulo a turn, and not at all at the pole where it means nothing.
bool same_directions(const std::vector<Direction>& measured, const std::vector<MaterialDirection>& model) {
  if (measured.size() != model.size()) return false;
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (std::abs(measured[i].theta - model[i].theta) > 1e-4) return false;
    if (measured[i].theta > 1e-6 &&
        std::abs(std::remainder(measured[i].phi - model[i].phi, 2 * std::numbers::pi)) > 1e-4) {
      return false;
    }
  }
  return true;
}

}  // namespace

BtfDataset load_measurement_of(const Material& material, const std::string& path, const std::string& option) {
  std::vector<std::string> warnings;
  BtfDataset dataset = load_btf(path, {}, warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!same_directions(dataset.lights(), material.lights) ||
      !same_directions(dataset.views(), material.views)) {
    throw CommandError(
        option + " " + path + ": its light and view directions are not the material's (" +
        std::to_string(dataset.lights().size()) + " x " + std::to_string(dataset.views().size()) +
        " against " + std::to_string(material.lights.size()) + " x " + std::to_string(material.views.size()) +
        "); give the BTF the material was analysed from");
  }
  return dataset;
}

}  // namespace carbtf::cli
