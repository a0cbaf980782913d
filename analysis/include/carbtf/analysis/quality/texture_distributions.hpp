// The texture measure rebuilt on distributions (issue 42, docs/design.md 5), beside the moment-based one of
// texture_similarity.hpp that `fidelity` and the analysis still use until this one ranks every case as a
// person does (what it does not yet: docs/design.md 5). A random-field model never equals its
// measurement pixel for pixel, so it compares whole distributions of what the eye compares, in CIE
// L*a*b* (D65), in six groups:
//  - colour:      the L*, a* and b* marginals (1D optimal transport of their quantiles, in Lab units);
//  - energy:      the L* band energy per octave and the a* and b* band energy per octave, in dB, down to
//                 periods of a quarter of a 256-pixel image (the coarsest octave that 8 pixels of the
//                 pyramid still hold);
//  - responses:   the shape of each octave's oriented band responses (complex Gabor filters at 0, 45,
//                 90 and 135 degrees on a Laplacian pyramid), each orientation scaled to unit RMS: sparse,
//                 heavy-tailed responses are edges, a Gaussian field's are Gaussian;
//  - local energy: the shape of each octave's local-energy distribution (the responses' modulus over the
//                 orientations, over its mean): flat cells against creases;
//  - coherence:   what only structure has: local energy that persists across adjacent octaves, and that
//                 lights adjacent and orthogonal orientations together (Portilla and Simoncelli 2000),
//                 as correlations, pooled over orientations so that a quarter turn leaves them;
//  - orientation: which way the texture runs and is lit: each orientation's energy against its octave's,
//                 and the skewness of its odd response (relief lit from one side has bright rising edges
//                 and soft falling ones along the light; a Gaussian field has none, a quarter turn moves it).
// Each feature difference is divided by what a person calls a clear difference and saturated at 4 of
// those; a group is the RMS of its features, and the distance a weighted mean of the groups in which the
// structure groups (responses, local energy, coherence) count most. Phase-randomising an image keeps the
// energy and loses the structure groups; a 1-pixel blur, a 10% gain and a 10 degree hue shift move energy
// or colour a little and keep the structure (the ranking tests,
// tests/analysis/test_texture_distributions.cpp, and docs/design.md 5). A pair of 256^2 images takes
// about 45 ms on one core of this machine.
//
// Images are linear RGB, row-major, 3 floats per pixel, at least 16 x 16; the two may differ in size.
// Thread safety: pure functions.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace carbtf {

struct DistributionStatistics {
  std::uint32_t octaves = 0;
  std::array<std::vector<float>, 3> lab_quantiles;  // L*, a*, b*: kQuantiles each
  std::array<double, 3> lab_mean{};
  std::vector<double> energy_db;         // L*, octave-major: octaves x 4 orientations, 10 log10(mean |z|^2)
  std::vector<double> chroma_energy_db;  // a* then b*, one per octave
  std::vector<double> chroma_deviation;  // a* then b*, one per octave: the band's std in Lab units
  std::vector<std::vector<float>>
      response_quantiles;  // per octave: the real responses, each orientation at unit RMS
  std::vector<std::vector<float>> energy_quantiles;  // per octave: local energy over its mean
  std::vector<double> cross_scale;                   // per adjacent octave pair: correlation of local energy
  std::vector<double> cross_orientation;  // per octave: adjacent then orthogonal orientations' correlation
  std::vector<double>
      odd_skewness;  // octave-major, per orientation: skewness of the odd (imaginary) response
};

struct DistributionDistance {
  static constexpr std::size_t kGroups = 6;
  static constexpr std::array<const char*, kGroups> kGroupNames{"colour",       "energy",    "responses",
                                                                "local_energy", "coherence", "orientation"};
  std::array<double, kGroups> groups{};
  double total = 0.0;  // weighted mean over the groups
};

struct DistributionOptions {
  std::uint32_t octaves = 6;  // at most; clipped to what the image holds (its coarsest level at least 8 px)
};

// Throws std::invalid_argument for an image under 16 x 16 or a buffer too small.
DistributionStatistics distribution_statistics(std::span<const float> rgb, std::uint32_t width,
                                               std::uint32_t height, const DistributionOptions& options = {});
// Both from the same options and images large enough for the same octaves; throws otherwise.
DistributionDistance distribution_distance(const DistributionStatistics& a, const DistributionStatistics& b);

}  // namespace carbtf
