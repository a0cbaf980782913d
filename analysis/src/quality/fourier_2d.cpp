#include "fourier_2d.hpp"

#include <algorithm>

#include <unsupported/Eigen/FFT>

namespace carbtf::detail {

void fourier_2d(ComplexField& data, std::uint32_t width, std::uint32_t height, bool inverse) {
  Eigen::FFT<double> fft;
  ComplexField line, transformed;
  auto run = [&] { inverse ? fft.inv(transformed, line) : fft.fwd(transformed, line); };
  line.resize(width);
  for (std::uint32_t r = 0; r < height; ++r) {
    std::copy_n(data.begin() + static_cast<std::ptrdiff_t>(std::size_t{r} * width), width, line.begin());
    run();
    std::copy_n(transformed.begin(), width,
                data.begin() + static_cast<std::ptrdiff_t>(std::size_t{r} * width));
  }
  line.resize(height);
  for (std::uint32_t c = 0; c < width; ++c) {
    for (std::uint32_t r = 0; r < height; ++r) line[r] = data[std::size_t{r} * width + c];
    run();
    for (std::uint32_t r = 0; r < height; ++r) data[std::size_t{r} * width + c] = transformed[r];
  }
}

}  // namespace carbtf::detail
