// Pixel-wise conformance of a synthesized image against a reference (docs/design.md 5): the largest and the
// RMS absolute difference, each divided by the reference's standard deviation in the same channel, so
// that the figures mean the same for every band, scale and material.
#pragma once

#include <cstdint>
#include <span>

namespace carbtf::reference {

struct ConformanceError {
  double max_relative = 0.0;     // max |test - reference| / std, over channels
  double rms_relative = 0.0;     // RMS over all values of (test - reference) / std of its channel
  double reference_std = 0.0;    // the smallest channel std (the denominator that matters most)
  std::uint64_t non_finite = 0;  // test values that are NaN or infinite
  bool within(double tolerance) const noexcept { return non_finite == 0 && max_relative <= tolerance; }
};

// `test` and `reference` hold `channels` interleaved channels of the same pixels. A channel whose
// reference is constant uses std 1 (its errors are then absolute).
ConformanceError conformance_error(std::span<const float> test, std::span<const double> reference,
                                   std::uint32_t channels);
ConformanceError conformance_error(std::span<const float> test, std::span<const float> reference,
                                   std::uint32_t channels);

// The worse of two (for aggregating over images).
ConformanceError worst_of(const ConformanceError& a, const ConformanceError& b);

}  // namespace carbtf::reference
