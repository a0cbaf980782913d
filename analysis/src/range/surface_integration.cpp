#include "carbtf/analysis/range/surface_integration.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <unsupported/Eigen/FFT>
#include <vector>

namespace carbtf {
namespace {

using Complex = std::complex<double>;

// In-place 2D FFT of a row-major rows x cols array.
void fft2(std::vector<Complex>& data, std::size_t rows, std::size_t cols, bool inverse) {
  Eigen::FFT<double> fft;
  std::vector<Complex> in, out;
  for (std::size_t r = 0; r < rows; ++r) {
    in.assign(data.begin() + static_cast<std::ptrdiff_t>(r * cols),
              data.begin() + static_cast<std::ptrdiff_t>((r + 1) * cols));
    inverse ? fft.inv(out, in) : fft.fwd(out, in);
    std::copy(out.begin(), out.end(), data.begin() + static_cast<std::ptrdiff_t>(r * cols));
  }
  for (std::size_t c = 0; c < cols; ++c) {
    in.resize(rows);
    for (std::size_t r = 0; r < rows; ++r) in[r] = data[r * cols + c];
    inverse ? fft.inv(out, in) : fft.fwd(out, in);
    for (std::size_t r = 0; r < rows; ++r) data[r * cols + c] = out[r];
  }
}

// The derivative's frequency response, i d(w): d = 2 sin(w / 2) with the sign of the centred frequency
// w in (-pi, pi]. It matches the true derivative (w) at low frequencies and stays away from zero up to
// Nyquist, so noise in the normals is never amplified by more than 1 / d there (the central
// difference, sin w, vanishes at Nyquist and would amplify it without bound).
double derivative(std::size_t index, std::size_t size) {
  const double k =
      index <= size / 2 ? static_cast<double>(index) : static_cast<double>(index) - static_cast<double>(size);
  const double w = 2.0 * std::numbers::pi * k / static_cast<double>(size);
  return 2.0 * std::sin(0.5 * w);
}

}  // namespace

Plane integrate_normals(std::span<const float> normals, std::uint32_t width, std::uint32_t height) {
  const std::size_t pixels = std::size_t{width} * height;
  if (normals.size() < pixels * 3 || pixels == 0)
    throw std::invalid_argument("integrate_normals: the normal map is empty or too small");
  // Gradients in image coordinates: dh/dcol = -nx / nz, dh/drow = +ny / nz (row grows downwards, y up).
  std::vector<Complex> p(pixels), q(pixels);
  for (std::size_t i = 0; i < pixels; ++i) {
    const double nz = std::max(double{normals[i * 3 + 2]}, 0.1);
    p[i] = -double{normals[i * 3]} / nz;
    q[i] = double{normals[i * 3 + 1]} / nz;
  }
  fft2(p, height, width, false);
  fft2(q, height, width, false);
  std::vector<Complex> h(pixels);
  for (std::size_t r = 0; r < height; ++r) {
    const double dy = derivative(r, height);
    for (std::size_t c = 0; c < width; ++c) {
      const double dx = derivative(c, width);
      const double denominator = dx * dx + dy * dy;
      const std::size_t i = r * width + c;
      // Least squares: H = conj(D) . G / |D|^2, D = i d.
      h[i] = denominator > 0.0 ? (Complex(0.0, -dx) * p[i] + Complex(0.0, -dy) * q[i]) / denominator
                               : Complex(0.0);
    }
  }
  fft2(h, height, width, true);
  Plane heights(height, width);
  for (std::size_t r = 0; r < height; ++r)
    for (std::size_t c = 0; c < width; ++c)
      heights(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = h[r * width + c].real();
  heights -= heights.mean();
  return heights;
}

}  // namespace carbtf
