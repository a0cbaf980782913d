// A texture-similarity measure between two images of one material that have no pixel correspondence
// (docs: docs/design.md 5, issue 13). A random-field model never equals its measurement pixel for pixel, so
// the measure compares what the eye compares, as statistics of CIE L*a*b* (D65) images, in five groups:
//  - colour:      the Lab mean (CIE76 delta E);
//  - contrast:    the std of L*, its mean local (8x8) contrast, and the std of the 4x4-block means of
//                 L*, a* and b* (the coarse structure that white noise lacks; chroma only there, since
//                 the eye resolves colour far more coarsely than lightness), as log ratios;
//  - bands:       oriented sub-band energies of L* in dB (octaves x 4 orientations), and the a* and b*
//                 energies per octave;
//  - orientation: the skewness of the L* derivative in 4 directions (relief lit from one side makes
//                 the derivative towards the light skewed) and each band's energy against its octave's
//                 mean (which way the texture runs);
//  - structure:   what a Gaussian field with the same spectrum lacks: skewness and kurtosis of L*, a*,
//                 b* (specks, creases), the kurtosis of each octave's band (edges and cells are sparse),
//                 the correlation of band envelopes across adjacent octaves (an edge lights every
//                 octave at once), the kurtosis of the derivatives and the spread of local contrast.
// Each group is an RMS over its features, each feature divided by what a person would call a clear
// difference and saturated at 4 of those (the constants in texture_similarity.cpp); the distance is
// the weighted mean over the groups, orientation counting twice (a BTF is a function of direction). Phase-randomising an image keeps colour, contrast and bands, and loses
// the structure group and the derivative skewness.
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

struct TextureStatistics {
  std::array<double, 3> mean{};       // L*, a*, b*
  std::array<double, 3> deviation{};  // population std
  std::array<double, 3> skewness{};
  std::array<double, 3> kurtosis{};
  std::vector<double> band_db;          // L*, octave-major: octaves x 4 orientations, 10 log10(energy)
  std::vector<double> chroma_band_db;   // a* then b*, one per octave
  std::vector<double> band_kurtosis;    // L*, one per octave (mean over orientations)
  std::vector<double> cross_scale;      // L*, (octaves - 1) x 4
  std::array<double, 4> derivative_skewness{};  // L* derivative along 0, 45, 90, 135 degrees
  std::array<double, 4> derivative_kurtosis{};
  std::array<double, 2> local_contrast{};  // mean and coefficient of variation of the 8x8-window L* std
  // Std of the 4x4-block means of L*, a*, b*: the contrast of the coarse structure (which white noise
  // lacks), and the chroma contrast at the scales the eye resolves colour at.
  std::array<double, 3> coarse_deviation{};
};

struct TextureDistance {
  // One per group, in the order of the header comment.
  static constexpr std::size_t kGroups = 5;
  static constexpr std::array<const char*, kGroups> kGroupNames{"colour", "contrast", "bands", "orientation", "structure"};
  std::array<double, kGroups> groups{};
  double total = 0.0;  // weighted mean over the groups
};

struct TextureSimilarityOptions {
  std::uint32_t octaves = 4;  // clipped to what the image size holds (at least 2 octaves, 16 px)
};

// Throws std::invalid_argument for an image under 16 x 16 or a buffer too small.
TextureStatistics texture_statistics(std::span<const float> rgb, std::uint32_t width, std::uint32_t height,
                                     const TextureSimilarityOptions& options = {});
// Both from the same options and images large enough for the same octaves; throws otherwise.
TextureDistance texture_distance(const TextureStatistics& a, const TextureStatistics& b);

// A linear RGB image with its size, for the references below.
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
// The region [row0, row0 + height) x [col0, col0 + width).
RgbField crop(const RgbField& image, std::uint32_t row0, std::uint32_t col0, std::uint32_t width, std::uint32_t height);

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
// The model image must be at least as large as half the measurement. Seeded references.
struct CalibratedFidelity {
  double floor = 0.0, ceiling = 0.0, model = 0.0, gaussian = 0.0;
  double rel = 0.0, gaussian_rel = 0.0, structure = 0.0;
  TextureDistance parts;           // of the model
  TextureDistance gaussian_parts;  // of the Gaussian reference
  bool beats_gaussian() const { return model < gaussian; }
};
CalibratedFidelity calibrated_fidelity(const RgbField& model, const RgbField& measured, std::uint64_t seed = 1,
                                       const TextureSimilarityOptions& options = {});

}  // namespace carbtf
