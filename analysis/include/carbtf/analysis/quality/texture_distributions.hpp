// The texture measure on distributions (issue 42, docs/design.md 5). A random-field model never equals its
// measurement pixel for pixel, so it compares whole distributions of what the eye compares, in CIE
// L*a*b* (D65), in eight groups:
//  - colour:       the L*, a* and b* marginals (1D optimal transport of their quantiles, in Lab units);
//  - energy:       the L* band energy per octave and the a* and b* band energy per octave, in dB, down to
//                  periods of a quarter of a 256-pixel image (the coarsest octave that 8 pixels of the
//                  pyramid still hold);
//  - grain:        fine grain the reference lacks: the finest octave's energy over the next one's, where
//                  the candidate's is the steeper (one-sided, so the distance is not symmetric: a blur that
//                  loses grain is a mild change, speckle on smooth cells is not);
//  - responses:    the shape of each octave's oriented band responses (complex Gabor filters at 0, 45, 90
//                  and 135 degrees on a Laplacian pyramid), each orientation scaled to unit RMS: sparse,
//                  heavy-tailed responses are edges, a Gaussian field's are Gaussian;
//  - local energy: the shape of each octave's local-energy distribution (the responses' modulus over the
//                  orientations, over its mean): flat cells against creases;
//  - coherence:    what only structure has: local energy that persists across adjacent octaves, and that
//                  lights adjacent and orthogonal orientations together (Portilla and Simoncelli 2000), as
//                  correlations, pooled over orientations so that a quarter turn leaves them;
//  - orientation:  which way the texture runs: each orientation's energy against its octave's;
//  - lighting:     which way it is lit, as a vector per octave (the first circular harmonic over the
//                  orientations): of the odd response's skewness (relief lit from one side has bright
//                  rising edges and soft falling ones), and of its mean over the band's darkest and
//                  brightest tenths (a cast shadow lies away from the light). A Gaussian field has none; a
//                  quarter turn or another light direction turns it.
// Each feature difference is divided by what a person calls a clear difference and saturated at 4 of
// those. The structure statistics' scales grow with their sampling noise over a band's pixels, and a
// level under 2,048 pixels counts in proportion, so that the content two crops of one texture happen to
// hold at coarse octaves is not read as change. A group is the RMS of its features, the distance a
// weighted mean of the groups, in which the structure groups count most. Phase-randomising an image keeps
// the energy and loses the structure groups; a 1-pixel blur, a 10% gain and a 10 degree hue shift move
// energy or colour a little and keep the structure (the ranking tests,
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
  std::vector<double> band_pixels;  // per octave: the band's pixel count, which sets its statistics' noise
  std::vector<double>
      odd_skewness;  // octave-major, per orientation: skewness of the odd (imaginary) response
  // octave-major, per orientation: the odd response's mean over the band's darkest (brightest) tenth,
  // over its RMS
  std::vector<double> dark_side, bright_side;
};

struct DistributionDistance {
  static constexpr std::size_t kGroups = 8;
  static constexpr std::array<const char*, kGroups> kGroupNames{
      "colour", "energy", "grain", "responses", "local_energy", "coherence", "orientation", "lighting"};
  std::array<double, kGroups> groups{};
  double total = 0.0;  // weighted mean over the groups
};

struct DistributionOptions {
  std::uint32_t octaves = 6;  // at most; clipped to what the image holds (its coarsest level at least 8 px)
};

// Throws std::invalid_argument for an image under 16 x 16 or a buffer too small.
DistributionStatistics distribution_statistics(std::span<const float> rgb, std::uint32_t width,
                                               std::uint32_t height, const DistributionOptions& options = {});
// a is the candidate (a model, a distorted image), b the reference (the measurement); both from the same
// options and images large enough for the same octaves; throws otherwise.
DistributionDistance distribution_distance(const DistributionStatistics& a, const DistributionStatistics& b);

// What the energy and lighting groups compare at one octave (0: the finest, periods of 4 pixels; each
// next one doubles them), for reading where a distance comes from (`carbtf fidelity`'s
// fidelity_octaves.csv). Throws std::out_of_range for an octave the statistics do not hold.
struct OctaveProfile {
  double energy_db = 0.0;  // the L* band energy over the four orientations, in dB
  // The a* and b* band energies in dB (the chroma the grain and energy groups compare).
  std::array<double, 2> chroma_energy_db{};
  // Which way the octave is lit: the first circular harmonic over the orientations (x right, y up) of
  // the odd response's skewness, and of its mean over the band's darkest and brightest tenths in units
  // of its RMS. It points along the light's azimuth or against it; the Gaussian field's is near 0.
  std::array<double, 2> skewness{}, dark_side{}, bright_side{};
};
OctaveProfile octave_profile(const DistributionStatistics& s, std::size_t octave);

}  // namespace carbtf
