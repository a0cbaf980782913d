#include "carbtf/reference/car_synthesis.hpp"

#include <stdexcept>
#include <string>

#include <carbtf_steps.h>

#include "carbtf/reference/noise.hpp"

namespace carbtf::reference {
namespace {

// The recursion over the CAR region, stored with its frame (pad rows above, pad columns each side) so
// that every tap reads memory: the frame holds zeros or the block initialization values.
template <typename Real>
struct PaddedField {
  TextureRegion car;
  std::int64_t pad = 1;
  std::int64_t pitch = 0;
  std::vector<Real> values;  // (car.rows + pad) x pitch
};

template <typename Real>
PaddedField<Real> run_recursion(const CarBandModel& band, const CarFieldBlock& block) {
  PaddedField<Real> f;
  f.car = car_region({block.row0, block.col0, block.height, block.width}, block.margin);
  f.pad = car_frame_pad(band.neighbourhood);
  f.pitch = f.car.cols + 2 * f.pad;
  f.values.assign(static_cast<std::size_t>((f.car.rows + f.pad) * f.pitch), Real{0});
  if (!block.frame.empty()) {
    const std::uint64_t expected = car_frame_floats(f.car, static_cast<std::uint32_t>(f.pad));
    if (block.frame.size() != expected) {
      throw std::invalid_argument("CAR field " + std::to_string(block.field_id) +
                                  ": block initialization frame has " + std::to_string(block.frame.size()) +
                                  " values, expected " + std::to_string(expected));
    }
    std::size_t i = 0;
    for (std::int64_t r = 0; r < f.pad; ++r) {
      for (std::int64_t c = 0; c < f.pitch; ++c)
        f.values[static_cast<std::size_t>(r * f.pitch + c)] = block.frame[i++];
    }
    for (std::int64_t r = f.pad; r < f.pad + f.car.rows; ++r) {
      for (std::int64_t c = 0; c < f.pad; ++c)
        f.values[static_cast<std::size_t>(r * f.pitch + c)] = block.frame[i++];
      for (std::int64_t c = f.pad + f.car.cols; c < f.pitch; ++c)
        f.values[static_cast<std::size_t>(r * f.pitch + c)] = block.frame[i++];
    }
  }
  const std::size_t gammas = band.gamma.size();
  std::vector<std::int64_t> tap(gammas);
  std::vector<Real> gamma(gammas);
  for (std::size_t k = 0; k < gammas; ++k) {
    tap[k] = std::int64_t{band.neighbourhood[k].dr} * f.pitch + band.neighbourhood[k].dc;
    gamma[k] = static_cast<Real>(band.gamma[k]);
  }
  const Real sigma = static_cast<Real>(band.sigma);
  for (std::int64_t r = 0; r < f.car.rows; ++r) {
    Real* row = f.values.data() + (r + f.pad) * f.pitch + f.pad;
    NoiseRowCursor noise(block.seed, block.field_id, static_cast<std::int32_t>(f.car.row0 + r),
                         static_cast<std::int32_t>(f.car.col0));
    for (std::int64_t c = 0; c < f.car.cols; ++c) {
      Real acc{0};
      for (std::size_t k = 0; k < gammas; ++k) acc = gpu::carbtf_weighted_add(acc, gamma[k], row[c + tap[k]]);
      row[c] = gpu::carbtf_car_value(acc, sigma, static_cast<Real>(noise.next()));
    }
  }
  return f;
}

template <typename Real>
void synthesize(const CarBandModel& band, const CarFieldBlock& block, std::span<Real> out) {
  if (out.size() < std::size_t{block.width} * block.height)
    throw std::invalid_argument("CAR block output is too small");
  const PaddedField<Real> f = run_recursion<Real>(band, block);
  const Real mean = static_cast<Real>(band.mean);
  const std::int64_t first = (f.pad + block.margin) * f.pitch + f.pad + block.margin;
  for (std::uint32_t r = 0; r < block.height; ++r) {
    for (std::uint32_t c = 0; c < block.width; ++c) {
      out[std::size_t{r} * block.width + c] =
          mean + f.values[static_cast<std::size_t>(first + r * f.pitch + c)];
    }
  }
}

}  // namespace

void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<float> out) {
  synthesize(band, block, out);
}
void synthesize_car_block(const CarBandModel& band, const CarFieldBlock& block, std::span<double> out) {
  synthesize(band, block, out);
}

CarFieldValues synthesize_car_field(const CarBandModel& band, const CarFieldBlock& block) {
  PaddedField<float> f = run_recursion<float>(band, block);
  return {{f.car.row0 - f.pad, f.car.col0 - f.pad, f.car.rows + f.pad, f.pitch}, std::move(f.values)};
}

}  // namespace carbtf::reference
