#include "carbtf/analysis/quality/texture_similarity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "carbtf/analysis/segmentation/lab_histogram.hpp"
#include "fourier_2d.hpp"

namespace carbtf {
namespace {

using detail::ComplexField;

// What a person would call a clear difference, per feature; a group's distance is the RMS of the
// feature differences divided by these.
constexpr double kColourScale = 3.0;              // delta E
constexpr double kContrastScale = 0.33647;        // ln 1.4: a 40% contrast change
constexpr double kBandScale = 2.0;                // dB
constexpr double kChromaBandScale = 3.0;          // dB
constexpr double kAnisotropyScale = 0.5;          // dB, of one orientation against its octave's mean
constexpr double kDerivativeSkewnessScale = 0.1;
constexpr double kSkewnessScale = 0.5;
constexpr double kKurtosisScale = 0.69315;        // ln 2
constexpr double kCrossScaleScale = 0.25;         // correlation
constexpr double kLocalContrastCvScale = 0.2;
constexpr double kSaturation = 4.0;
constexpr double kVisibleChromaDeviation = 3.0;  // Lab units
constexpr double kMinDeviation = 0.5;             // Lab units: a flatter channel compares as this flat

constexpr std::uint32_t kOrientations = 4;
constexpr std::uint32_t kWindow = 8;  // local-contrast window
constexpr std::uint32_t kBlock = 4;   // coarse-contrast block

struct Moments {
  double mean = 0.0, deviation = 0.0, skewness = 0.0, kurtosis = 3.0;
};

template <typename Values>
Moments moments_of(const Values& values) {
  Moments m;
  const auto n = static_cast<double>(values.size());
  if (values.size() == 0) return m;
  for (double v : values) m.mean += v;
  m.mean /= n;
  double m2 = 0.0, m3 = 0.0, m4 = 0.0;
  for (double v : values) {
    const double d = v - m.mean;
    m2 += d * d;
    m3 += d * d * d;
    m4 += d * d * d * d;
  }
  m2 /= n;
  m3 /= n;
  m4 /= n;
  m.deviation = std::sqrt(m2);
  if (m2 > 1e-12) {
    m.skewness = m3 / (m2 * m.deviation);
    m.kurtosis = m4 / (m2 * m2);
  }
  return m;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const Moments ma = moments_of(a), mb = moments_of(b);
  if (ma.deviation < 1e-12 || mb.deviation < 1e-12) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - ma.mean) * (b[i] - mb.mean);
  return sum / (static_cast<double>(a.size()) * ma.deviation * mb.deviation);
}

std::uint32_t octaves_for(std::uint32_t width, std::uint32_t height, const TextureSimilarityOptions& options) {
  // The coarsest octave's band (1/2^(o+2) to 1/2^(o+1) cycles per pixel) needs a few periods in the image.
  const auto fit = static_cast<std::uint32_t>(std::floor(std::log2(std::min(width, height) / 4.0)));
  return std::max(2u, std::min(options.octaves, fit));
}

// Which octave and orientation a frequency falls in; octave -1 when it is in none (DC, the corners past
// 0.5 cycles, or coarser than the last octave). The orientation is of the half-plane angle, so
// (fx, fy) and (-fx, -fy) share it; `side` says which half-plane it is on.
struct BandIndex {
  int octave = -1;
  std::uint32_t orientation = 0;
  bool side = false;
};

BandIndex band_of(double fx, double fy, std::uint32_t octaves) {
  BandIndex index;
  const double radius = std::hypot(fx, fy);
  if (radius <= 0.0 || radius > 0.5) return index;
  const int octave = static_cast<int>(std::floor(std::log2(0.5 / radius)));
  if (octave < 0 || octave >= static_cast<int>(octaves)) return index;
  double angle = std::atan2(fy, fx);  // (-pi, pi]
  index.side = angle >= 0.0;
  if (angle < 0.0) angle += std::numbers::pi;
  index.octave = octave;
  index.orientation = static_cast<std::uint32_t>(std::lround(angle / (std::numbers::pi / kOrientations))) % kOrientations;
  return index;
}

// Energy (variance contributed) of the field in each octave x orientation, and optionally per octave.
std::vector<double> band_energies(const ComplexField& spectrum, std::uint32_t width, std::uint32_t height, std::uint32_t octaves,
                                  bool oriented) {
  std::vector<double> energy(octaves * (oriented ? kOrientations : 1), 0.0);
  const double n2 = static_cast<double>(width) * height * static_cast<double>(width) * height;
  for (std::uint32_t r = 0; r < height; ++r) {
    const double fy = detail::signed_frequency(r, height);
    for (std::uint32_t c = 0; c < width; ++c) {
      const BandIndex b = band_of(detail::signed_frequency(c, width), fy, octaves);
      if (b.octave < 0) continue;
      const std::size_t slot = oriented ? static_cast<std::size_t>(b.octave) * kOrientations + b.orientation : static_cast<std::size_t>(b.octave);
      energy[slot] += std::norm(spectrum[std::size_t{r} * width + c]) / n2;
    }
  }
  for (double& e : energy) e = 10.0 * std::log10(e + 1e-10);
  return energy;
}

std::vector<double> centred(const std::vector<double>& values, double mean) {
  std::vector<double> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) out[i] = values[i] - mean;
  return out;
}

ComplexField spectrum_of(const std::vector<double>& field, std::uint32_t width, std::uint32_t height) {
  ComplexField data(field.begin(), field.end());
  detail::fourier_2d(data, width, height);
  return data;
}

double log_ratio(double a, double b, double floor) { return std::log(std::max(a, floor) / std::max(b, floor)); }

}  // namespace

TextureStatistics texture_statistics(std::span<const float> rgb, std::uint32_t width, std::uint32_t height,
                                     const TextureSimilarityOptions& options) {
  if (width < 16 || height < 16) throw std::invalid_argument("texture statistics: images must be at least 16x16");
  const std::size_t pixels = std::size_t{width} * height;
  if (rgb.size() < pixels * 3) throw std::invalid_argument("texture statistics: image buffer too small");
  std::array<std::vector<double>, 3> lab;
  for (auto& channel : lab) channel.resize(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    const auto v = linear_srgb_to_lab(std::max(rgb[p * 3], 0.0f), std::max(rgb[p * 3 + 1], 0.0f), std::max(rgb[p * 3 + 2], 0.0f));
    for (int c = 0; c < 3; ++c) lab[c][p] = v[c];
  }
  TextureStatistics s;
  for (int c = 0; c < 3; ++c) {
    const Moments m = moments_of(lab[c]);
    s.mean[c] = m.mean;
    s.deviation[c] = m.deviation;
    s.skewness[c] = m.skewness;
    s.kurtosis[c] = m.kurtosis;
  }
  const std::uint32_t octaves = octaves_for(width, height, options);
  const ComplexField luminance = spectrum_of(centred(lab[0], s.mean[0]), width, height);
  s.band_db = band_energies(luminance, width, height, octaves, true);
  for (int c = 1; c < 3; ++c) {
    const std::vector<double> chroma = band_energies(spectrum_of(centred(lab[c], s.mean[c]), width, height), width, height, octaves, false);
    s.chroma_band_db.insert(s.chroma_band_db.end(), chroma.begin(), chroma.end());
  }

  // Analytic band signals (one half-plane of each oriented band): the real part is the band, the
  // modulus its envelope.
  std::vector<std::vector<double>> envelopes(std::size_t{octaves} * kOrientations);
  s.band_kurtosis.assign(octaves, 0.0);
  for (std::uint32_t o = 0; o < octaves; ++o) {
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      ComplexField band(pixels, 0.0);
      for (std::uint32_t r = 0; r < height; ++r) {
        const double fy = detail::signed_frequency(r, height);
        for (std::uint32_t c = 0; c < width; ++c) {
          const BandIndex b = band_of(detail::signed_frequency(c, width), fy, octaves);
          if (b.octave == static_cast<int>(o) && b.orientation == k && b.side) band[std::size_t{r} * width + c] = luminance[std::size_t{r} * width + c];
        }
      }
      detail::fourier_2d(band, width, height, true);
      std::vector<double> real(pixels), envelope(pixels);
      for (std::size_t p = 0; p < pixels; ++p) {
        real[p] = band[p].real();
        envelope[p] = std::abs(band[p]);
      }
      s.band_kurtosis[o] += moments_of(real).kurtosis / kOrientations;
      envelopes[std::size_t{o} * kOrientations + k] = std::move(envelope);
    }
  }
  for (std::uint32_t o = 0; o + 1 < octaves; ++o) {
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      s.cross_scale.push_back(correlation(envelopes[std::size_t{o} * kOrientations + k], envelopes[std::size_t{o + 1} * kOrientations + k]));
    }
  }

  // Derivatives along 0, 45, 90 and 135 degrees (x right, y up: row - 1 is up).
  const int steps[kOrientations][2] = {{0, 1}, {-1, 1}, {-1, 0}, {-1, -1}};  // (drow, dcol)
  for (std::uint32_t k = 0; k < kOrientations; ++k) {
    std::vector<double> derivative;
    derivative.reserve(pixels);
    for (std::uint32_t r = 1; r + 1 < height; ++r) {
      for (std::uint32_t c = 1; c + 1 < width; ++c) {
        const std::size_t next = std::size_t(static_cast<int>(r) + steps[k][0]) * width + std::size_t(static_cast<int>(c) + steps[k][1]);
        derivative.push_back(lab[0][next] - lab[0][std::size_t{r} * width + c]);
      }
    }
    const Moments m = moments_of(derivative);
    s.derivative_skewness[k] = m.skewness;
    s.derivative_kurtosis[k] = m.kurtosis;
  }
  std::vector<double> local;
  for (std::uint32_t r = 0; r + kWindow <= height; r += kWindow) {
    for (std::uint32_t c = 0; c + kWindow <= width; c += kWindow) {
      std::vector<double> window;
      for (std::uint32_t y = 0; y < kWindow; ++y) {
        for (std::uint32_t x = 0; x < kWindow; ++x) window.push_back(lab[0][std::size_t{r + y} * width + c + x]);
      }
      local.push_back(moments_of(window).deviation);
    }
  }
  const Moments spread = moments_of(local);
  s.local_contrast = {spread.mean, spread.mean > 1e-9 ? spread.deviation / spread.mean : 0.0};
  for (int channel = 0; channel < 3; ++channel) {
    std::vector<double> blocks;
    for (std::uint32_t r = 0; r + kBlock <= height; r += kBlock) {
      for (std::uint32_t c = 0; c + kBlock <= width; c += kBlock) {
        double sum = 0.0;
        for (std::uint32_t y = 0; y < kBlock; ++y) {
          for (std::uint32_t x = 0; x < kBlock; ++x) sum += lab[channel][std::size_t{r + y} * width + c + x];
        }
        blocks.push_back(sum / (kBlock * kBlock));
      }
    }
    s.coarse_deviation[channel] = moments_of(blocks).deviation;
  }
  return s;
}

TextureDistance texture_distance(const TextureStatistics& a, const TextureStatistics& b) {
  if (a.band_db.size() != b.band_db.size() || a.band_kurtosis.size() != b.band_kurtosis.size() ||
      a.chroma_band_db.size() != b.chroma_band_db.size() || a.cross_scale.size() != b.cross_scale.size()) {
    throw std::invalid_argument("texture statistics from different options or image sizes");
  }
  const std::size_t octaves = a.band_kurtosis.size();
  // Each group: the RMS of its features, each in units of a clear difference and saturated at
  // kSaturation, so that one feature gone far (a band emptied by a blur) cannot outweigh the rest.
  struct Group {
    double sum = 0.0;
    double weight = 0.0;
    void add(double scaled, double feature_weight = 1.0) {
      const double v = std::min(std::abs(scaled), kSaturation);
      sum += feature_weight * v * v;
      weight += feature_weight;
    }
    double value() const { return weight > 0.0 ? std::sqrt(sum / weight) : 0.0; }
  };
  // A band's dB difference counts by the larger of its two shares of the energy, times the band
  // count: a change in a band that holds little of either image's energy is masked by the others
  // (a blur that empties an already faint octave is less visible than noise that fills it).
  // The eye's contrast sensitivity falls towards the finest octave (half and quarter of the sampling
  // rate): its changes count less.
  const auto sensitivity = [](std::size_t octave) { return octave == 0 ? 0.35 : octave == 1 ? 0.7 : 1.0; };
  const auto add_band_differences = [&](Group& group, const std::vector<double>& da, const std::vector<double>& db, double scale,
                                        std::size_t bands_per_octave) {
    double total_a = 0.0, total_b = 0.0;
    for (std::size_t i = 0; i < da.size(); ++i) {
      total_a += std::pow(10.0, da[i] / 10.0);
      total_b += std::pow(10.0, db[i] / 10.0);
    }
    for (std::size_t i = 0; i < da.size(); ++i) {
      const double share = std::max(std::pow(10.0, da[i] / 10.0) / std::max(total_a, 1e-30), std::pow(10.0, db[i] / 10.0) / std::max(total_b, 1e-30));
      group.add((da[i] - db[i]) / scale, sensitivity(i / bands_per_octave % octaves) * share * static_cast<double>(da.size()));
    }
  };
  std::array<Group, TextureDistance::kGroups> g;
  double delta_e = 0.0;
  for (int c = 0; c < 3; ++c) delta_e += (a.mean[c] - b.mean[c]) * (a.mean[c] - b.mean[c]);
  g[0].add(std::sqrt(delta_e) / kColourScale);

  g[1].add(log_ratio(a.deviation[0], b.deviation[0], kMinDeviation) / kContrastScale);
  g[1].add(log_ratio(a.local_contrast[0], b.local_contrast[0], kMinDeviation) / kContrastScale);
  // Chroma contrast under a few Lab units is hard to see: it counts in proportion.
  for (int c = 0; c < 3; ++c) {
    const double weight = c == 0 ? 1.0 : std::min(1.0, std::max(a.coarse_deviation[c], b.coarse_deviation[c]) / kVisibleChromaDeviation);
    g[1].add(log_ratio(a.coarse_deviation[c], b.coarse_deviation[c], kMinDeviation) / kContrastScale, weight);
  }

  add_band_differences(g[2], a.band_db, b.band_db, kBandScale, kOrientations);
  add_band_differences(g[2], a.chroma_band_db, b.chroma_band_db, kChromaBandScale, 1);

  // Orientation: which way the relief is lit and which way the texture runs.
  for (std::uint32_t k = 0; k < kOrientations; ++k) g[3].add((a.derivative_skewness[k] - b.derivative_skewness[k]) / kDerivativeSkewnessScale);
  for (std::size_t o = 0; o < octaves; ++o) {
    double mean_a = 0.0, mean_b = 0.0;
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      mean_a += a.band_db[o * kOrientations + k] / kOrientations;
      mean_b += b.band_db[o * kOrientations + k] / kOrientations;
    }
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      g[3].add(((a.band_db[o * kOrientations + k] - mean_a) - (b.band_db[o * kOrientations + k] - mean_b)) / kAnisotropyScale);
    }
  }

  // Structure beyond the spectrum: what a Gaussian field with the same spectrum lacks. A chroma
  // channel flatter than 1 Lab unit has the skewness and kurtosis of its noise, so it counts less.
  for (int c = 0; c < 3; ++c) {
    const double weight = c == 0 ? 1.0 : std::min(1.0, std::min(a.deviation[c], b.deviation[c]));
    g[4].add(weight * (a.skewness[c] - b.skewness[c]) / kSkewnessScale);
    g[4].add(weight * log_ratio(a.kurtosis[c], b.kurtosis[c], 1.0) / kKurtosisScale);
  }
  for (std::size_t o = 0; o < octaves; ++o) g[4].add(log_ratio(a.band_kurtosis[o], b.band_kurtosis[o], 1.0) / kKurtosisScale);
  for (std::size_t i = 0; i < a.cross_scale.size(); ++i) g[4].add((a.cross_scale[i] - b.cross_scale[i]) / kCrossScaleScale);
  for (std::uint32_t k = 0; k < kOrientations; ++k) g[4].add(log_ratio(a.derivative_kurtosis[k], b.derivative_kurtosis[k], 1.0) / kKurtosisScale);
  g[4].add((a.local_contrast[1] - b.local_contrast[1]) / kLocalContrastCvScale);

  // Orientation counts twice: a BTF is a function of the light and view directions, and a texture lit
  // from the wrong side is the wrong BTF value however right its statistics are otherwise.
  constexpr std::array<double, TextureDistance::kGroups> kWeights{1.0, 1.0, 1.0, 2.0, 1.0};
  double weights = 0.0;
  for (double w : kWeights) weights += w;
  TextureDistance d;
  for (std::size_t i = 0; i < g.size(); ++i) {
    d.groups[i] = g[i].value();
    d.total += kWeights[i] * d.groups[i] / weights;
  }
  return d;
}

}  // namespace carbtf
