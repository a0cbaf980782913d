#include "carbtf/reference/conformance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace carbtf::reference {
namespace {

template <typename Reference>
ConformanceError compare(std::span<const float> test, std::span<const Reference> reference,
                         std::uint32_t channels) {
  if (channels == 0 || test.size() != reference.size() || test.size() % channels != 0) {
    throw std::invalid_argument("conformance: test and reference differ in size or channel count");
  }
  const std::size_t pixels = test.size() / channels;
  std::vector<double> mean(channels, 0.0), variance(channels, 0.0);
  for (std::size_t i = 0; i < reference.size(); ++i) mean[i % channels] += static_cast<double>(reference[i]);
  for (double& m : mean) m /= static_cast<double>(std::max<std::size_t>(pixels, 1));
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double d = static_cast<double>(reference[i]) - mean[i % channels];
    variance[i % channels] += d * d;
  }
  ConformanceError error;
  error.reference_std = INFINITY;
  std::vector<double> scale(channels);
  for (std::uint32_t c = 0; c < channels; ++c) {
    const double std_dev = std::sqrt(variance[c] / static_cast<double>(std::max<std::size_t>(pixels, 1)));
    scale[c] = std_dev > 0.0 ? 1.0 / std_dev : 1.0;
    error.reference_std = std::min(error.reference_std, std_dev);
  }
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < test.size(); ++i) {
    if (!std::isfinite(test[i])) {
      ++error.non_finite;
      continue;
    }
    const double relative =
        std::abs(static_cast<double>(test[i]) - static_cast<double>(reference[i])) * scale[i % channels];
    error.max_relative = std::max(error.max_relative, relative);
    sum_squares += relative * relative;
  }
  error.rms_relative = test.empty() ? 0.0 : std::sqrt(sum_squares / static_cast<double>(test.size()));
  if (test.empty()) error.reference_std = 0.0;
  return error;
}

}  // namespace

ConformanceError conformance_error(std::span<const float> test, std::span<const double> reference,
                                   std::uint32_t channels) {
  return compare(test, reference, channels);
}

ConformanceError conformance_error(std::span<const float> test, std::span<const float> reference,
                                   std::uint32_t channels) {
  return compare(test, reference, channels);
}

ConformanceError worst_of(const ConformanceError& a, const ConformanceError& b) {
  ConformanceError w;
  w.max_relative = std::max(a.max_relative, b.max_relative);
  w.rms_relative = std::max(a.rms_relative, b.rms_relative);
  // A default-constructed error (reference_std 0) is the identity.
  w.reference_std = a.reference_std == 0.0   ? b.reference_std
                    : b.reference_std == 0.0 ? a.reference_std
                                             : std::min(a.reference_std, b.reference_std);
  w.non_finite = a.non_finite + b.non_finite;
  return w;
}

}  // namespace carbtf::reference
