#include "carbtf/engine/internal/synthesis_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "carbtf/engine/material/car_stability.hpp"

namespace carbtf {

TextureRegion coarse_support(const TextureRegion& fine) {
  const std::int64_t r0 = floor_half(fine.row0 - 1), r1 = floor_half(fine.row0 + fine.rows + 1) + 1;
  const std::int64_t c0 = floor_half(fine.col0 - 1), c1 = floor_half(fine.col0 + fine.cols + 1) + 1;
  return {r0, c0, r1 - r0, c1 - c0};
}

std::uint32_t band_burn_in(const CarBandModel& band, std::uint32_t limit) {
  if (band.neighbourhood.empty() || limit == 0) return 0;
  // rho^m <= residual exactly when every root lies within residual^(1 / m); the smallest such m by
  // bisection over [1, limit]. 64 column frequencies: the margin is a bound on a transient, not a
  // stability verdict, and a plan asks this of every band.
  constexpr int kFrequencies = 64;
  const std::vector<double> gamma(band.gamma.begin(), band.gamma.end());
  const auto enough = [&](std::uint32_t m) {
    return car_roots_within(band.neighbourhood, gamma, std::pow(kBurnInResidual, 1.0 / m), kFrequencies);
  };
  if (!enough(limit)) return limit;
  std::uint32_t low = 0, high = limit;  // enough(high); not enough(low) or low == 0
  while (high - low > 1) {
    const std::uint32_t middle = low + (high - low) / 2;
    (enough(middle) ? high : low) = middle;
  }
  return high;
}

std::vector<TextureRegion> level_regions(const TextureRegion& block, std::uint32_t levels) {
  std::vector<TextureRegion> regions{block};
  for (std::uint32_t level = 1; level < levels; ++level) regions.push_back(coarse_support(regions.back()));
  return regions;
}

std::uint32_t default_periodic_overlap(std::uint32_t width, std::uint32_t height) {
  return std::clamp(std::min(width, height) / 8u, 4u, 64u);
}

TextureRegion synthesized_region(const SynthesisBlock& block) {
  return {block.row0, block.col0, std::int64_t{block.height} + block.periodic_overlap,
          std::int64_t{block.width} + block.periodic_overlap};
}

bool within_texture_coordinates(const SynthesisBlock& block) {
  // [first, first + count) within the two's complement 32-bit rows or columns.
  const auto within = [](std::int64_t first, std::int64_t count) {
    return first >= std::numeric_limits<std::int32_t>::min() &&
           first <= std::int64_t{std::numeric_limits<std::int32_t>::max()} - count + 1;  // no overflow
  };
  const TextureRegion region = synthesized_region(block);
  const std::int64_t margin = block.margin;
  return within(region.row0 - margin, region.rows + margin) &&
         within(region.col0 - margin, region.cols + 2 * margin);
}

float collapsed_band_mean(const SubspaceModel& model, std::uint32_t channel) {
  float sum = 0.0f;
  for (std::uint32_t level = model.levels; level-- > 0;)
    sum += model.bands[std::size_t{level} * model.channels + channel].mean;
  return sum;
}

std::uint32_t car_frame_pad(std::span<const CarNeighbour> neighbourhood) {
  int pad = 1;
  for (const CarNeighbour& n : neighbourhood) pad = std::max({pad, -int{n.dr}, std::abs(int{n.dc})});
  return static_cast<std::uint32_t>(pad);
}

std::uint32_t car_wavefront_skew(std::span<const CarNeighbour> neighbourhood) {
  int skew = 1;
  for (const CarNeighbour& n : neighbourhood) {
    if (n.dr >= 0) continue;
    const int up = -int{n.dr};
    const int need = int{n.dc} + 1;  // the step gap a * up must exceed dc
    if (need > 0) skew = std::max(skew, (need + up - 1) / up);
  }
  return static_cast<std::uint32_t>(skew);
}

TextureRegion car_region(const TextureRegion& level_region, std::uint32_t margin) {
  return {level_region.row0 - margin, level_region.col0 - margin, level_region.rows + margin,
          level_region.cols + 2 * std::int64_t{margin}};
}

std::uint64_t car_frame_floats(const TextureRegion& car, std::uint32_t pad) {
  return static_cast<std::uint64_t>(pad * (car.cols + 2 * std::int64_t{pad}) +
                                    car.rows * 2 * std::int64_t{pad});
}

BlockFrameLayout block_frame_layout(const Material& material, const SynthesisBlock& block,
                                    std::span<const std::uint32_t> subspaces) {
  BlockFrameLayout layout;
  for (const std::uint32_t s : subspaces) {
    const SubspaceModel& model = material.subspaces[s];
    const auto regions = level_regions(synthesized_region(block), model.levels);
    for (std::uint32_t level = 0; level < model.levels; ++level) {
      for (std::uint32_t channel = 0; channel < model.channels; ++channel) {
        BlockFrameField field;
        field.subspace = s;
        field.level = level;
        field.channel = channel;
        const CarBandModel& band = model.bands[std::size_t{level} * model.channels + channel];
        field.car = car_region(regions[level], band_burn_in(band, block.margin));
        field.pad = car_frame_pad(band.neighbourhood);
        field.offset = layout.floats;
        layout.floats += car_frame_floats(field.car, field.pad);
        layout.fields.push_back(field);
      }
    }
  }
  return layout;
}

bool extract_car_frame(const TextureRegion& car, std::uint32_t pad, std::span<const float> source,
                       const TextureRegion& source_region, std::span<float> out) {
  const std::int64_t top = car.row0 - pad, left = car.col0 - pad;
  const std::int64_t right = car.col0 + car.cols + pad, bottom = car.row0 + car.rows;
  if (top < source_region.row0 || left < source_region.col0 ||
      bottom > source_region.row0 + source_region.rows || right > source_region.col0 + source_region.cols ||
      out.size() < car_frame_floats(car, pad) ||
      source.size() < static_cast<std::uint64_t>(source_region.rows * source_region.cols)) {
    return false;
  }
  auto at = [&](std::int64_t row, std::int64_t col) {
    return source[static_cast<std::size_t>((row - source_region.row0) * source_region.cols +
                                           (col - source_region.col0))];
  };
  std::size_t i = 0;
  for (std::int64_t row = top; row < car.row0; ++row) {
    for (std::int64_t col = left; col < right; ++col) out[i++] = at(row, col);
  }
  for (std::int64_t row = car.row0; row < bottom; ++row) {
    for (std::int64_t col = left; col < car.col0; ++col) out[i++] = at(row, col);
    for (std::int64_t col = car.col0 + car.cols; col < right; ++col) out[i++] = at(row, col);
  }
  return true;
}

}  // namespace carbtf
