// The references that calibrate the texture measure (texture_distributions.hpp, docs/design.md 5), and the
// calibrated fidelity of a model image built from them: disjoint crops of the measurement (what "the
// same material" scores), the phase-randomised image (the best a stationary Gaussian field can do) and
// white noise of the measured colours.
//
// Images are linear RGB, row-major, 3 floats per pixel. Thread safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

#include "carbtf/analysis/quality/texture_distributions.hpp"

namespace carbtf {

// A linear RGB image with its size.
struct RgbField {
  std::vector<float> rgb;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

// The best stationary Gaussian texture of `image`: the same Fourier amplitudes per channel of its
// sRGB-encoded values (close to L*'s) and random phases, the same phases in all three channels (so the
// colour cross-spectra stay). Seeded.
RgbField phase_randomised(const RgbField& image, std::uint64_t seed);
// White Gaussian noise with the image's mean and colour covariance (linear RGB, clamped at 0). Seeded.
RgbField white_noise_like(const RgbField& image, std::uint64_t seed);
// The region [row0, row0 + height) x [col0, col0 + width); throws std::invalid_argument outside the image.
RgbField crop(const RgbField& image, std::uint32_t row0, std::uint32_t col0, std::uint32_t width,
              std::uint32_t height);

// The calibrated fidelity of a model image against a measured image (docs/design.md 5):
//  - the measured image is split into two halves along its longer side; half A is the reference;
//  - floor:    d(half B, A), what "the same material" scores;
//  - ceiling:  d(white noise like B, A);
//  - gaussian: d(phase-randomised B, A), the most a Gaussian field alone can reach;
//  - model:    d(the model cropped to A's size from its centre, A);
//  - rel = (model - floor) / (ceiling - floor), and gaussian_rel alike: 0 is as good as the
//    measurement itself, 1 as bad as white noise;
//  - structure = (model - floor) / (gaussian - floor), the structure score s: 0 indistinguishable from
//    the measurement, 1 no better than a Gaussian field, below 1 the model beats it.
// d is distribution_distance(candidate, A). The model image must be at least as large as half the
// measurement, and that half at least 16 x 16; throws std::invalid_argument otherwise. Seeded references.
struct CalibratedFidelity {
  double floor = 0.0, ceiling = 0.0, model = 0.0, gaussian = 0.0;
  double rel = 0.0, gaussian_rel = 0.0, structure = 0.0;
  DistributionDistance parts;           // of the model
  DistributionDistance gaussian_parts;  // of the Gaussian reference
  bool beats_gaussian() const { return model < gaussian; }
};
CalibratedFidelity calibrated_fidelity(const RgbField& model, const RgbField& measured,
                                       std::uint64_t seed = 1, const DistributionOptions& options = {});

}  // namespace carbtf
