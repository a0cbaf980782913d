#include "carbtf/analysis/model/collapse_calibration.hpp"

#include <algorithm>
#include <cmath>

#include "carbtf/analysis/model/pyramid.hpp"
#include "carbtf/reference/car_synthesis.hpp"

namespace carbtf {
namespace {

// Far from any seed a user picks by hand; only the statistics of these fields matter.
constexpr std::uint64_t kCalibrationSeed = 0x5eedca1bULL;
// The synthesized fields are at least this large per side, so that their variance is estimated
// within a few per cent however small the coarse level.
constexpr Eigen::Index kMinCalibrationSide = 256;

double variance(const Plane& p) {
  const double mean = p.mean();
  return (p - mean).square().mean();
}

// expand() applied `times` times, each step to twice the size (the analysis's own level sizes when
// `sizes` names them).
Plane expanded(Plane plane, const std::vector<std::pair<Eigen::Index, Eigen::Index>>& sizes) {
  for (auto it = sizes.rbegin(); it != sizes.rend(); ++it) plane = expand_plane(plane, it->first, it->second);
  return plane;
}

}  // namespace

std::vector<double> calibrate_collapse_variance(SubspaceModel& model, const std::vector<Plane>& bands,
                                                const std::vector<std::vector<Plane>>& pyramids) {
  std::vector<double> factors(model.bands.size(), 1.0);
  const std::uint32_t levels = model.levels;
  for (std::uint32_t channel = 0; channel < model.channels; ++channel) {
    const std::vector<Plane>& measured = pyramids[channel];
    if (measured.size() != levels) continue;
    std::vector<double> contribution(levels, 0.0);
    double contributions = 0.0;
    for (std::uint32_t level = 0; level < levels; ++level) {
      std::vector<std::pair<Eigen::Index, Eigen::Index>> sizes;
      for (std::uint32_t finer = 0; finer < level; ++finer)
        sizes.push_back({measured[finer].rows(), measured[finer].cols()});
      contribution[level] = variance(expanded(measured[level], sizes));
      contributions += contribution[level];
    }
    const double total = variance(bands[channel]);
    if (!(contributions > 0.0) || !(total > 0.0)) continue;
    for (std::uint32_t level = 0; level < levels; ++level) {
      CarBandModel& band = model.bands[std::size_t{level} * model.channels + channel];
      if (!(band.sigma > 0.0f) || (band.flags & car_band_constant)) continue;
      // The CAR field on a grid at least kMinCalibrationSide wide, expanded as often as the level is.
      const Eigen::Index rows = std::max(measured[level].rows(), kMinCalibrationSide);
      const Eigen::Index cols = std::max(measured[level].cols(), kMinCalibrationSide);
      reference::CarFieldBlock block;
      block.seed = kCalibrationSeed;
      block.field_id = level * 16 + channel;
      block.width = static_cast<std::uint32_t>(cols);
      block.height = static_cast<std::uint32_t>(rows);
      block.margin = 64;
      std::vector<double> values(static_cast<std::size_t>(rows * cols));
      reference::synthesize_car_block(band, block, values);
      Plane field = Eigen::Map<const Plane>(values.data(), rows, cols);
      std::vector<std::pair<Eigen::Index, Eigen::Index>> sizes;
      Eigen::Index r = rows, c = cols;
      for (std::uint32_t finer = 0; finer < level; ++finer) sizes.insert(sizes.begin(), {r *= 2, c *= 2});
      const double synthesized = variance(expanded(field, sizes));
      const double target = contribution[level] * total / contributions;
      if (!(synthesized > 0.0) || !(target > 0.0)) continue;
      const double factor = std::sqrt(target / synthesized);
      band.sigma = static_cast<float>(band.sigma * factor);
      factors[std::size_t{level} * model.channels + channel] = factor;
    }
  }
  return factors;
}

}  // namespace carbtf
