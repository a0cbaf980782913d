// Fidelity of a material against the measured BTF it models, as a person would judge it (docs/design.md 5,
// issue 13): the model and the measured images are drawn through the same render pass (a plane,
// orthographic, the measured view and light; at oblique views several samples per pixel, averaged as a
// camera pixel integrates its footprint), and the calibrated texture measure
// (analysis/quality/texture_references.hpp, on texture_distributions.hpp) compares them, beside the best
// stationary Gaussian texture. Serves `carbtf fidelity` and the demo.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/quality/texture_references.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf::cli {

struct FidelityPair {
  std::uint32_t light = 0;  // indices into the material's (and the dataset's) direction sets
  std::uint32_t view = 0;
  std::string label;
};

// The default spread over a material's directions: the top view under lights at 15, 45 and 75 degrees
// (the grazing one), and two oblique views (45 and 60 degrees) under a 45-degree light; each the
// measured direction nearest the wanted one.
std::vector<FidelityPair> default_fidelity_pairs(const Material& material);

// `count` measured pairs spread evenly over all lights x views (the R2 low-discrepancy sequence over
// their indices), the same for every run: a broader sample than the default five, on which a few pairs
// can sway a verdict (the specular lobe costs coast_sand_rocks on the five, most at the mirror pair, and
// helps it over 16 spread pairs). Views that cover under a third of the frame (over 70.5 degrees) are
// skipped; fewer where the dataset has fewer images, none where no view can be scored.
std::vector<FidelityPair> spread_fidelity_pairs(const Material& material, const BtfDataset& dataset,
                                                std::size_t count);

// Render samples per pixel side that integrate a camera pixel's footprint at a view `view_theta` (radians)
// from the normal: 1 where the footprint along the tilt, 1 / cos(theta) texels, is under 1.25 (views up
// to 37 degrees), else the power of two that covers it, at most 4 (2 at 45 and 60 degrees).
std::uint32_t camera_samples_per_side(double view_theta);

struct PairFidelity {
  FidelityPair pair;
  CalibratedFidelity result;
  RgbField model;     // the rendered model, cropped to where the plane covers the frame
  RgbField measured;  // the rendered measurement, same crop
  RgbField gaussian;  // the phase-randomised measurement: the best a Gaussian field alone can do
};

struct FidelityRunOptions {
  std::uint64_t seed = 1;  // synthesis and reference noise
  float parallax_scale = 1.0f;
  bool progress = true;  // a line per pair on stdout
};

// Synthesizes every subspace image at the measurement's size and scores each pair. Throws
// CommandError on engine failures and when a pair's image is missing from the dataset.
std::vector<PairFidelity> run_fidelity(Context& context, const Material& material, const BtfDataset& dataset,
                                       const std::vector<FidelityPair>& pairs,
                                       const FidelityRunOptions& options = {});

// "beats the Gaussian reference" or "does not beat the Gaussian reference": the verdict of one pair.
const char* verdict(const CalibratedFidelity& f);

// Mean and worst s and rel over the pairs, and how many pairs the model beats the Gaussian reference on
// (s < 1).
struct FidelitySummaryLine {
  double mean_structure = 0.0, worst_structure = 0.0;
  double mean_rel = 0.0, worst_rel = 0.0, mean_gaussian_rel = 0.0;
  std::size_t beats_gaussian = 0, pairs = 0;
};
FidelitySummaryLine summarize(const std::vector<PairFidelity>& results);
// "s mean 0.62, worst 0.91 (0: the measurement itself, 1: no better than a Gaussian field); rel mean
// 0.30, worst 0.41 (1: white noise), the Gaussian reference's 0.48; the model beats the Gaussian
// reference on 5 of 5 pairs": the one line `fidelity` and the demo print.
std::string summary_text(const FidelitySummaryLine& s);
// fidelity.md: a row per pair (s, rel, the Gaussian reference's rel, the verdict), the mean and worst.
std::string fidelity_markdown(const std::vector<PairFidelity>& results);

// One row per pair: measured | model | Gaussian reference, each cell padded to the largest crop, linear
// RGB, white between the cells, for write_rgb_image() to encode; the columns' titles drawn on top and
// each row's pair, s and verdict above it.
RgbField fidelity_grid(const std::vector<PairFidelity>& results);

// CSV with a header: pair, light and view in degrees, rel, s (structure), gaussian_rel, floor, ceiling,
// the Gaussian reference's and the model's distances, the model's groups and the reference's.
std::string fidelity_csv(const std::vector<PairFidelity>& results, const Material& material);

// fidelity_octaves.csv, where a pair's distance comes from: one row per pair and octave of the measure
// (octave_profile(), analysis/quality/texture_distributions.hpp), the octave's period in pixels, then
// for the model and for the measurement the L*, a* and b* band energies in dB and the lighting vectors
// (x, y) of the odd response's skewness and of its dark-side and bright-side means.
std::string fidelity_octaves_csv(const std::vector<PairFidelity>& results);

}  // namespace carbtf::cli
