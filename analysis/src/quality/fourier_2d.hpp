// Internal: 2D discrete Fourier transforms of row-major fields through Eigen's FFT (rows, then
// columns), shared by the quality measures and the normal integration's preconditioner
// (range/surface_integration.cpp).
#pragma once

#include <complex>
#include <cstdint>
#include <vector>

namespace carbtf::detail {

using ComplexField = std::vector<std::complex<double>>;

// In place; `inverse` includes the 1 / (width * height) factor.
void fourier_2d(ComplexField& data, std::uint32_t width, std::uint32_t height, bool inverse = false);

// Signed frequency of index i of an n-point transform, in cycles per sample: i / n or (i - n) / n.
inline double signed_frequency(std::uint32_t i, std::uint32_t n) {
  return (i <= n / 2 ? static_cast<double>(i) : static_cast<double>(i) - n) / n;
}

}  // namespace carbtf::detail
