// Photometric stereo (Woodham 1980; paper Sec. III, docs/design.md 4.2): per-pixel normals and albedo from
// the images of one view under many distant lights.
//
// Per pixel, on the grey value (mean of linear R, G, B) of each light l:
//   I_l = b . l_l + c,   b = albedo * normal, c an ambient offset (optional)
// solved by least squares (4x4 normal equations, LDLT) on the samples between two intensity
// quantiles of the pixel (shadows sit at the dark end, highlights at the bright end), then refined by
// rejecting outliers and refitting: samples darker than dark_fraction of the pixel's brightest (shadow),
// samples the fit puts near or past the terminator (n . l < min_cosine, where the clamp at zero breaks
// linearity), samples lit from within specular_cone_degrees of the view's mirror direction about the current
// normal (where a glossy lobe adds to the Lambertian term), and samples whose residual exceeds `rejection`
// robust standard deviations (1.4826 x median absolute residual): cast shadows below, specular highlights
// above. The colour albedo scales the grey albedo by the pixel's mean colour ratio over its inlier samples. A
// pixel with fewer inliers than unknowns keeps the normal (0, 0, 1) and is marked invalid.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"

namespace carbtf {

struct PhotometricStereoOptions {
  bool ambient_term = true;
  double dark_fraction = 0.02;
  double initial_dark_quantile = 0.3;     // the first fit skips the darkest 30% of samples
  double initial_bright_quantile = 0.75;  // and the brightest 25%
  double specular_cone_degrees = 30.0;    // lights this close to the mirror direction of the view
  double min_cosine = 0.1;
  double rejection = 3.0;
  int iterations = 4;
  unsigned threads = 0;
};

struct NormalMap {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> normals;          // width * height * 3, unit (x right, y up, z out of the surface)
  std::vector<float> albedo;           // width * height * 3, linear RGB
  std::vector<std::uint8_t> valid;     // width * height, 1 where the fit had enough inliers
  std::vector<std::uint16_t> inliers;  // width * height, samples used
};

// `images[l]` is width * height * 3 linear RGB lit from unit direction `lights[l]`; `mask` (optional,
// width * height) limits the work to non-zero pixels; `view_direction` is the unit direction towards
// the camera. Throws std::invalid_argument on mismatched
// sizes or fewer than 3 lights.
NormalMap photometric_stereo(const std::vector<std::span<const float>>& images,
                             const std::vector<std::array<double, 3>>& lights, std::uint32_t width,
                             std::uint32_t height, std::span<const std::uint8_t> mask,
                             const std::array<double, 3>& view_direction,
                             const PhotometricStereoOptions& options = {});

// The images of view `view` under every light present in the dataset (and its mask, if any).
NormalMap photometric_stereo(const BtfDataset& dataset, std::uint32_t view,
                             const PhotometricStereoOptions& options = {});

// The view nearest the surface normal: the default view for photometric stereo.
std::uint32_t top_view(const BtfDataset& dataset);

// Angular error in degrees between unit normals, per pixel where `valid` (empty: all) is non-zero.
std::vector<double> angular_errors_degrees(std::span<const float> normals, std::span<const float> truth,
                                           std::span<const std::uint8_t> valid = {});

}  // namespace carbtf
