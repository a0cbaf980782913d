#include "carbtf/analysis/reference/car_synthesis.hpp"

#include <stdexcept>
#include <vector>

#include "carbtf/analysis/reference/noise.hpp"

namespace carbtf::reference {
namespace {

template <typename Real>
void synthesize(const CarBandModel& band, const CarFieldBlock& block, std::span<Real> out) {
  if (out.size() < std::size_t{block.width} * block.height) throw std::invalid_argument("CAR block output is too small");
  const std::int64_t margin = block.margin;
  const std::int64_t rows = block.height + margin;
  const std::int64_t cols = block.width + 2 * margin;
  const std::int64_t top = std::int64_t{block.row0} - margin;
  const std::int64_t left = std::int64_t{block.col0} - margin;
  std::vector<Real> field(static_cast<std::size_t>(rows * cols), Real{0});
  auto at = [&](std::int64_t r, std::int64_t c) -> Real {
    return (r < 0 || c < 0 || c >= cols) ? Real{0} : field[static_cast<std::size_t>(r * cols + c)];
  };
  const auto gammas = band.gamma.size();
  const Real sigma = static_cast<Real>(band.sigma);
  for (std::int64_t r = 0; r < rows; ++r) {
    for (std::int64_t c = 0; c < cols; ++c) {
      Real acc{0};
      for (std::size_t k = 0; k < gammas; ++k) {
        acc = acc + static_cast<Real>(band.gamma[k]) * at(r + band.neighbourhood[k].dr, c + band.neighbourhood[k].dc);
      }
      const float e = gaussian_noise(block.seed, block.field_id, static_cast<std::int32_t>(top + r), static_cast<std::int32_t>(left + c));
      field[static_cast<std::size_t>(r * cols + c)] = acc + sigma * static_cast<Real>(e);
    }
  }
  const Real mean = static_cast<Real>(band.mean);
  for (std::uint32_t r = 0; r < block.height; ++r) {
    for (std::uint32_t c = 0; c < block.width; ++c) {
      out[std::size_t{r} * block.width + c] = mean + field[static_cast<std::size_t>((r + margin) * cols + c + margin)];
    }
  }
}

}  // namespace

void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<float> out) { synthesize(band, block, out); }
void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<double> out) { synthesize(band, block, out); }

}  // namespace carbtf::reference
