#include "carbtf/analysis/quality/texture_references.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "carbtf/analysis/btf/btf_dataset.hpp"  // the sRGB transfer function
#include "carbtf/reference/noise.hpp"
#include "fourier_2d.hpp"

namespace carbtf {

using detail::ComplexField;

RgbField crop(const RgbField& image, std::uint32_t row0, std::uint32_t col0, std::uint32_t width,
              std::uint32_t height) {
  if (std::size_t{row0} + height > image.height || std::size_t{col0} + width > image.width) {
    throw std::invalid_argument("crop: region outside the image");
  }
  RgbField out{std::vector<float>(std::size_t{width} * height * 3), width, height};
  for (std::uint32_t r = 0; r < height; ++r) {
    std::copy_n(
        image.rgb.begin() + static_cast<std::ptrdiff_t>((std::size_t{row0 + r} * image.width + col0) * 3),
        std::size_t{width} * 3, out.rgb.begin() + static_cast<std::ptrdiff_t>(std::size_t{r} * width * 3));
  }
  return out;
}

RgbField phase_randomised(const RgbField& image, std::uint64_t seed) {
  const std::uint32_t w = image.width, h = image.height;
  const std::size_t pixels = std::size_t{w} * h;
  // Randomised in sRGB-encoded values, which are close to perceptual (L*) ones, so that the Lab mean and
  // contrast the measure sees stay those of the image and few values leave [0, 1].
  // The phases of a real white-noise field's spectrum are Hermitian, so adding them keeps the result
  // real; adding the same phases to every channel keeps the channels' cross-spectra.
  ComplexField noise(pixels);
  for (std::uint32_t r = 0; r < h; ++r) {
    for (std::uint32_t c = 0; c < w; ++c)
      noise[std::size_t{r} * w + c] =
          reference::gaussian_noise(seed, 0, static_cast<std::int32_t>(r), static_cast<std::int32_t>(c));
  }
  detail::fourier_2d(noise, w, h);
  RgbField out{std::vector<float>(pixels * 3), w, h};
  for (int channel = 0; channel < 3; ++channel) {
    ComplexField data(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
      data[p] = linear_to_srgb(std::max(image.rgb[p * 3 + channel], 0.0f));
    detail::fourier_2d(data, w, h);
    for (std::size_t p = 1; p < pixels; ++p) {
      const double magnitude = std::abs(noise[p]);
      if (magnitude > 0.0) data[p] *= noise[p] / magnitude;
    }
    detail::fourier_2d(data, w, h, true);
    for (std::size_t p = 0; p < pixels; ++p)
      out.rgb[p * 3 + channel] = srgb_to_linear(std::clamp(static_cast<float>(data[p].real()), 0.0f, 1.0f));
  }
  return out;
}

RgbField white_noise_like(const RgbField& image, std::uint64_t seed) {
  const std::size_t pixels = std::size_t{image.width} * image.height;
  double mean[3] = {}, cov[3][3] = {};
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int i = 0; i < 3; ++i) mean[i] += image.rgb[p * 3 + i];
  }
  for (double& m : mean) m /= static_cast<double>(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        cov[i][j] +=
            (image.rgb[p * 3 + i] - mean[i]) * (image.rgb[p * 3 + j] - mean[j]) / static_cast<double>(pixels);
    }
  }
  // Cholesky of the 3x3 covariance, with a tiny ridge so that a grey image (rank 1) still factors.
  double l[3][3] = {};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j <= i; ++j) {
      double v = cov[i][j] + (i == j ? 1e-12 : 0.0);
      for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
      l[i][j] = i == j ? std::sqrt(std::max(v, 0.0)) : (l[j][j] > 0.0 ? v / l[j][j] : 0.0);
    }
  }
  RgbField out{std::vector<float>(pixels * 3), image.width, image.height};
  for (std::uint32_t r = 0; r < image.height; ++r) {
    for (std::uint32_t c = 0; c < image.width; ++c) {
      double z[3];
      for (std::uint32_t k = 0; k < 3; ++k)
        z[k] = reference::gaussian_noise(seed, 1 + k, static_cast<std::int32_t>(r),
                                         static_cast<std::int32_t>(c));
      const std::size_t p = std::size_t{r} * image.width + c;
      for (int i = 0; i < 3; ++i) {
        double v = mean[i];
        for (int k = 0; k <= i; ++k) v += l[i][k] * z[k];
        out.rgb[p * 3 + i] = std::max(0.0f, static_cast<float>(v));
      }
    }
  }
  return out;
}

CalibratedFidelity calibrated_fidelity(const RgbField& model, const RgbField& measured, std::uint64_t seed,
                                       const DistributionOptions& options) {
  const bool split_columns = measured.width >= measured.height;
  const std::uint32_t w = split_columns ? measured.width / 2 : measured.width;
  const std::uint32_t h = split_columns ? measured.height : measured.height / 2;
  if (model.width < w || model.height < h) {
    throw std::invalid_argument("calibrated fidelity: the model image (" + std::to_string(model.width) + "x" +
                                std::to_string(model.height) + ") is smaller than half the measurement (" +
                                std::to_string(w) + "x" + std::to_string(h) + ")");
  }
  const RgbField a = crop(measured, 0, 0, w, h);
  const RgbField b = split_columns ? crop(measured, 0, w, w, h) : crop(measured, h, 0, w, h);
  const DistributionStatistics reference = distribution_statistics(a.rgb, w, h, options);
  auto distance = [&](const RgbField& image) {
    return distribution_distance(distribution_statistics(image.rgb, w, h, options), reference);
  };
  CalibratedFidelity f;
  f.floor = distance(b).total;
  f.ceiling = distance(white_noise_like(b, seed)).total;
  f.gaussian_parts = distance(phase_randomised(b, seed));
  f.gaussian = f.gaussian_parts.total;
  f.parts = distance(crop(model, (model.height - h) / 2, (model.width - w) / 2, w, h));
  f.model = f.parts.total;
  const double range = std::max(f.ceiling - f.floor, 1e-9);
  f.rel = (f.model - f.floor) / range;
  f.gaussian_rel = (f.gaussian - f.floor) / range;
  f.structure = (f.model - f.floor) / std::max(f.gaussian - f.floor, 1e-9);
  return f;
}

}  // namespace carbtf
