// The segmentation feature of one BTF image (docs/design.md 4.1): cumulative histograms of CIE L*, a*, b*
// (D65 white, linear sRGB primaries), concatenated. L* bins span [0, 100],
// a* and b* span
// [-110, 110]; values outside fall in the end bins. Each cumulative histogram rises to 1, so the
// Euclidean distance between features compares whole distributions (a Cramer-von Mises-like distance).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace carbtf {

// CIE L*a*b* of a linear sRGB colour (D65).
std::array<float, 3> linear_srgb_to_lab(float r, float g, float b);
// Its inverse: the linear sRGB colour of CIE L*a*b* (D65); out-of-gamut colours come out as they are.
std::array<double, 3> lab_to_linear_srgb(double l, double a, double b);

// Feature of a width x height linear RGB image, from every `stride`-th pixel in each direction;
// 3 * bins values: L*, then a*, then b*.
std::vector<float> lab_cumulative_histogram(std::span<const float> rgb, std::uint32_t width,
                                            std::uint32_t height, std::uint32_t bins,
                                            std::uint32_t stride = 1);

}  // namespace carbtf
