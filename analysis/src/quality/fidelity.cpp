#include "carbtf/analysis/quality/fidelity.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <vector>


#include "carbtf/analysis/segmentation/lab_histogram.hpp"
#include "fourier_2d.hpp"

namespace carbtf {
namespace {

using detail::ComplexField;

struct LabImage {
  std::vector<double> channel[3];
  double mean[3] = {};
  double deviation[3] = {};
};

LabImage to_lab(std::span<const float> rgb, std::uint32_t width, std::uint32_t height) {
  if (width < 2 || height < 2) throw std::invalid_argument("fidelity: images must be at least 2x2");
  const std::size_t pixels = std::size_t{width} * height;
  if (rgb.size() < pixels * 3) throw std::invalid_argument("fidelity: image buffer too small");
  LabImage lab;
  for (auto& c : lab.channel) c.resize(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    const auto v = linear_srgb_to_lab(rgb[p * 3], rgb[p * 3 + 1], rgb[p * 3 + 2]);
    for (int c = 0; c < 3; ++c) lab.channel[c][p] = v[c];
  }
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, square = 0.0;
    for (double v : lab.channel[c]) sum += v;
    lab.mean[c] = sum / static_cast<double>(pixels);
    for (double v : lab.channel[c]) square += (v - lab.mean[c]) * (v - lab.mean[c]);
    lab.deviation[c] = std::sqrt(square / static_cast<double>(pixels));
  }
  return lab;
}

// Radially averaged power spectrum of a zero-mean field, normalised to unit total power, as log10 per
// ring of normalised frequency |f| in [0, 0.5] (the DC term left out).
std::vector<double> log_radial_spectrum(const std::vector<double>& field, double mean, std::uint32_t width,
                                        std::uint32_t height, std::uint32_t bins) {
  ComplexField data(field.size());
  for (std::size_t i = 0; i < field.size(); ++i) data[i] = field[i] - mean;
  detail::fourier_2d(data, width, height);
  std::vector<double> power(bins, 0.0);
  std::vector<double> count(bins, 0.0);
  double total = 0.0;
  for (std::uint32_t r = 0; r < height; ++r) {
    const double fy = detail::signed_frequency(r, height);
    for (std::uint32_t c = 0; c < width; ++c) {
      if (r == 0 && c == 0) continue;
      const double fx = detail::signed_frequency(c, width);
      const double radius = std::sqrt(fx * fx + fy * fy);
      if (radius > 0.5) continue;  // the corners: not every direction reaches them
      const auto bin = std::min<std::uint32_t>(bins - 1, static_cast<std::uint32_t>(radius / 0.5 * bins));
      const double p = std::norm(data[std::size_t{r} * width + c]);
      power[bin] += p;
      count[bin] += 1.0;
      total += p;
    }
  }
  std::vector<double> spectrum(bins);
  // A flat field has no power: compare it as white rather than dividing by zero.
  const double floor = 1e-12;
  for (std::uint32_t b = 0; b < bins; ++b) {
    const double mean_power = count[b] > 0 ? power[b] / count[b] : 0.0;
    const double normalised = total > 0 ? mean_power * static_cast<double>(field.size()) / total : 1.0;
    spectrum[b] = std::log10(std::max(normalised, floor));
  }
  return spectrum;
}

}  // namespace

FidelityStatistics fidelity_statistics(std::span<const float> rgb, std::uint32_t width, std::uint32_t height,
                                       const FidelityOptions& options) {
  if (options.spectrum_bins == 0 || options.histogram_bins == 0)
    throw std::invalid_argument("fidelity: bins must be positive");
  const LabImage lab = to_lab(rgb, width, height);
  FidelityStatistics statistics;
  for (int c = 0; c < 3; ++c) {
    statistics.mean[c] = lab.mean[c];
    statistics.deviation[c] = lab.deviation[c];
  }
  statistics.log_spectrum =
      log_radial_spectrum(lab.channel[0], lab.mean[0], width, height, options.spectrum_bins);
  statistics.cumulative_histogram = lab_cumulative_histogram(rgb, width, height, options.histogram_bins);
  return statistics;
}

FidelityError fidelity_error(const FidelityStatistics& a, const FidelityStatistics& b) {
  if (a.log_spectrum.size() != b.log_spectrum.size() ||
      a.cumulative_histogram.size() != b.cumulative_histogram.size() || a.log_spectrum.empty() ||
      a.cumulative_histogram.empty()) {
    throw std::invalid_argument("fidelity: statistics computed with different options");
  }
  FidelityError e;
  double square = 0.0;
  for (int c = 0; c < 3; ++c) {
    square += (a.mean[c] - b.mean[c]) * (a.mean[c] - b.mean[c]);
    // Relative to the measurement's contrast, floored at 1 Lab unit: a nearly flat channel (the chroma
    // of a grey material) then compares in absolute units instead of amplifying sampling noise.
    const double relative = std::abs(a.deviation[c] - b.deviation[c]) / std::max(b.deviation[c], 1.0);
    e.std_relative = std::max(e.std_relative, relative);
  }
  e.delta_e = std::sqrt(square);
  const std::size_t rings = a.log_spectrum.size();
  for (std::size_t i = 0; i < rings; ++i) e.spectrum_l1 += std::abs(a.log_spectrum[i] - b.log_spectrum[i]);
  e.spectrum_l1 /= static_cast<double>(rings);
  const std::size_t bins = a.cumulative_histogram.size() / 3;
  const double width[3] = {100.0 / bins, 220.0 / bins,
                           220.0 / bins};  // the feature's bin widths in Lab units
  for (std::size_t c = 0; c < 3; ++c) {
    double distance = 0.0;
    for (std::size_t i = 0; i < bins; ++i) {
      distance += std::abs(double(a.cumulative_histogram[c * bins + i]) -
                           double(b.cumulative_histogram[c * bins + i]));
    }
    e.histogram_w1 += distance * width[c] / 3.0;
  }
  return e;
}

FidelityError fidelity_error(std::span<const float> model, std::uint32_t model_width,
                             std::uint32_t model_height, std::span<const float> measured,
                             std::uint32_t measured_width, std::uint32_t measured_height,
                             const FidelityOptions& options) {
  return fidelity_error(fidelity_statistics(model, model_width, model_height, options),
                        fidelity_statistics(measured, measured_width, measured_height, options));
}

void FidelitySummary::add(const FidelityError& e) {
  const double n = pairs;
  auto update = [&](double& average, double& largest, double value) {
    average = (average * n + value) / (n + 1.0);
    largest = std::max(largest, value);
  };
  update(mean.delta_e, worst.delta_e, e.delta_e);
  update(mean.std_relative, worst.std_relative, e.std_relative);
  update(mean.spectrum_l1, worst.spectrum_l1, e.spectrum_l1);
  update(mean.histogram_w1, worst.histogram_w1, e.histogram_w1);
  ++pairs;
}

}  // namespace carbtf
