// Fidelity of a model image against a measured image of the same (light, view) (DESIGN.md 5). A
// random-field model never equals the measurement pixel for pixel, so these compare statistics, all in
// CIE L*a*b* (D65) of linear sRGB:
//  - colour: CIE76 delta E between the mean Lab colours;
//  - contrast: relative error of the standard deviation of L*, a* and b*, the worst of the three, each
//    relative to the measured std floored at 1 Lab unit (a nearly flat chroma channel compares in
//    absolute units);
//  - structure: L1 distance between the radially averaged log10 power spectra of L*, each normalised to
//    unit total power (so contrast does not count twice) over `spectrum_bins` rings of normalised
//    frequency [0, 0.5] (so images of different sizes compare), averaged over the rings;
//  - distribution: L1 distance between the cumulative Lab histograms (the segmentation feature), times
//    the bin width: the Wasserstein-1 distance in Lab units, averaged over L*, a* and b*.
// Images are linear RGB, row-major, 3 floats per pixel; the two may differ in size.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace carbtf {

struct FidelityError {
  double delta_e = 0.0;
  double std_relative = 0.0;
  double spectrum_l1 = 0.0;
  double histogram_w1 = 0.0;
};

struct FidelityOptions {
  std::uint32_t spectrum_bins = 24;
  std::uint32_t histogram_bins = 64;
};

// What the measures need of one image, so that each image is analysed once however many pairs use it.
struct FidelityStatistics {
  double mean[3] = {};                      // L*, a*, b*
  double deviation[3] = {};                 // population std of L*, a*, b*
  std::vector<double> log_spectrum;         // per ring
  std::vector<float> cumulative_histogram;  // lab_cumulative_histogram()
};

// Throws std::invalid_argument for an image smaller than 2 x 2, a buffer too small or zero bins.
FidelityStatistics fidelity_statistics(std::span<const float> rgb, std::uint32_t width, std::uint32_t height,
                                       const FidelityOptions& options = {});
// Both from the same options.
FidelityError fidelity_error(const FidelityStatistics& model, const FidelityStatistics& measured);

FidelityError fidelity_error(std::span<const float> model, std::uint32_t model_width,
                             std::uint32_t model_height, std::span<const float> measured,
                             std::uint32_t measured_width, std::uint32_t measured_height,
                             const FidelityOptions& options = {});

// Mean and worst of each measure over several pairs.
struct FidelitySummary {
  FidelityError mean;
  FidelityError worst;
  std::uint32_t pairs = 0;
  void add(const FidelityError& e);  // accumulates; mean is final after the last add
};

}  // namespace carbtf
