#include "carbtf/analysis/quality/texture_distributions.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "carbtf/analysis/segmentation/lab_histogram.hpp"

namespace carbtf {
namespace {

// What a person calls a clear difference, per feature (the calibration: docs/design.md 5).
constexpr double kColourScale = 2.0;        // Lab units of 1D transport between marginals
constexpr double kEnergyScale = 3.0;        // dB of an octave's L* energy
constexpr double kChromaEnergyScale = 4.0;  // dB of an octave's a* or b* energy
constexpr double kVisibleChroma = 3.0;      // Lab units: a chroma band fainter than this counts in proportion
constexpr double kResponseScale = 0.08;     // transport between unit-RMS response distributions
constexpr double kLocalEnergyScale = 0.1;   // transport between mean-1 local-energy distributions
constexpr double kCoherenceScale = 0.15;    // correlation
constexpr double kOrientationScale = 2.0;   // dB, of one orientation against its octave's mean
constexpr double kOddSkewnessScale = 0.15;
// A feature counts at most this many clear differences, so that one feature gone far (a band emptied by a
// blur) cannot outweigh the rest; the energy group's limit is higher, since white noise (10-20 dB off in
// the finest and coarsest octaves) is further from any material than another material is.
constexpr double kSaturation = 4.0;
constexpr double kEnergySaturation = 8.0;
// colour, energy, responses, local energy, coherence, orientation
constexpr std::array<double, DistributionDistance::kGroups> kGroupWeights{1.0, 1.5, 2.0, 2.0, 1.5, 1.0};

constexpr std::size_t kQuantiles = 32;
constexpr std::size_t kMaxSamples = 8192;  // per distribution; a regular subsample of larger levels
constexpr std::uint32_t kOrientations = 4;
constexpr int kRadius = 4;                // of the Gabor kernels
constexpr double kGaborSigma = 1.5;       // pixels of the pyramid level
constexpr double kGaborFrequency = 0.25;  // cycles per pixel of the level: periods 4 * 2^octave
constexpr std::uint32_t kCoarsestSide = 8;

struct Level {
  std::uint32_t width = 0, height = 0;
  std::vector<float> values;
  float at(int r, int c) const {
    // Mirrored at the borders: crops are not periodic.
    const int w = static_cast<int>(width), h = static_cast<int>(height);
    r = r < 0 ? -r : (r >= h ? 2 * h - 2 - r : r);
    c = c < 0 ? -c : (c >= w ? 2 * w - 2 - c : c);
    return values[static_cast<std::size_t>(std::clamp(r, 0, h - 1)) * width +
                  static_cast<std::size_t>(std::clamp(c, 0, w - 1))];
  }
};

// The binomial [1 4 6 4 1] / 16 blur, separable, mirrored borders.
Level blurred(const Level& in) {
  static constexpr float k[5] = {1 / 16.f, 4 / 16.f, 6 / 16.f, 4 / 16.f, 1 / 16.f};
  Level tmp = in, out = in;
  const int w = static_cast<int>(in.width), h = static_cast<int>(in.height);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      float sum = 0.f;
      for (int i = -2; i <= 2; ++i) sum += k[i + 2] * in.at(r, c + i);
      tmp.values[static_cast<std::size_t>(r) * in.width + static_cast<std::size_t>(c)] = sum;
    }
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      float sum = 0.f;
      for (int i = -2; i <= 2; ++i) sum += k[i + 2] * tmp.at(r + i, c);
      out.values[static_cast<std::size_t>(r) * in.width + static_cast<std::size_t>(c)] = sum;
    }
  return out;
}

Level decimated(const Level& blurred_level) {
  Level out{(blurred_level.width + 1) / 2, (blurred_level.height + 1) / 2, {}};
  out.values.resize(std::size_t{out.width} * out.height);
  for (std::uint32_t r = 0; r < out.height; ++r)
    for (std::uint32_t c = 0; c < out.width; ++c)
      out.values[std::size_t{r} * out.width + c] =
          blurred_level.values[std::size_t{2 * r} * blurred_level.width + 2 * c];
  return out;
}

// Per level: the band-pass (level minus its blur), and the next level.
struct Pyramid {
  std::vector<Level> bands;
};

Pyramid laplacian_pyramid(Level level, std::uint32_t octaves) {
  Pyramid p;
  for (std::uint32_t o = 0; o < octaves; ++o) {
    Level smooth = blurred(level);
    Level band = level;
    for (std::size_t i = 0; i < band.values.size(); ++i) band.values[i] -= smooth.values[i];
    p.bands.push_back(std::move(band));
    // Blurred once more before decimation (a 9-tap binomial in all): with the 5-tap blur alone a
    // one-pixel shift of the sampling grid moved the distance by a quarter of the floor (aliasing).
    if (o + 1 < octaves) level = decimated(blurred(smooth));
  }
  return p;
}

using Complex = std::complex<float>;

// 1D Gabor taps: a Gaussian times exp(i 2 pi f x), for frequency f along this axis.
std::array<Complex, 2 * kRadius + 1> gabor_taps(double frequency) {
  std::array<Complex, 2 * kRadius + 1> taps{};
  for (int x = -kRadius; x <= kRadius; ++x) {
    const double g = std::exp(-0.5 * x * x / (kGaborSigma * kGaborSigma));
    taps[static_cast<std::size_t>(x + kRadius)] =
        Complex(static_cast<float>(g * std::cos(2 * std::numbers::pi * frequency * x)),
                static_cast<float>(g * std::sin(2 * std::numbers::pi * frequency * x)));
  }
  return taps;
}

// The complex response of `band` to the Gabor filter of orientation k (0, 45, 90, 135 degrees; x right,
// y up), separable as the product of a horizontal and a vertical complex 1D filter.
std::vector<Complex> oriented_response(const Level& band, std::uint32_t k) {
  const double angle = k * std::numbers::pi / kOrientations;
  const auto horizontal = gabor_taps(kGaborFrequency * std::cos(angle));
  const auto vertical = gabor_taps(-kGaborFrequency * std::sin(angle));  // row index grows downwards
  const int w = static_cast<int>(band.width), h = static_cast<int>(band.height);
  std::vector<Complex> rows(band.values.size()), out(band.values.size());
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      Complex sum{};
      for (int i = -kRadius; i <= kRadius; ++i)
        sum += horizontal[static_cast<std::size_t>(i + kRadius)] * band.at(r, c + i);
      rows[static_cast<std::size_t>(r) * band.width + static_cast<std::size_t>(c)] = sum;
    }
  auto row_at = [&](int r, int c) {
    r = r < 0 ? -r : (r >= h ? 2 * h - 2 - r : r);
    return rows[static_cast<std::size_t>(std::clamp(r, 0, h - 1)) * band.width + static_cast<std::size_t>(c)];
  };
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      Complex sum{};
      for (int i = -kRadius; i <= kRadius; ++i)
        sum += vertical[static_cast<std::size_t>(i + kRadius)] * row_at(r + i, c);
      out[static_cast<std::size_t>(r) * band.width + static_cast<std::size_t>(c)] = sum;
    }
  return out;
}

// kQuantiles quantiles at (i + 0.5) / kQuantiles of `values` (sorted in place), interpolated.
std::vector<float> quantiles_of(std::vector<float>& values) {
  std::sort(values.begin(), values.end());
  std::vector<float> q(kQuantiles, 0.f);
  if (values.empty()) return q;
  for (std::size_t i = 0; i < kQuantiles; ++i) {
    const double at = (static_cast<double>(i) + 0.5) / kQuantiles * static_cast<double>(values.size()) - 0.5;
    const auto low =
        static_cast<std::size_t>(std::clamp(std::floor(at), 0.0, static_cast<double>(values.size() - 1)));
    const std::size_t high = std::min(low + 1, values.size() - 1);
    const double t = std::clamp(at - static_cast<double>(low), 0.0, 1.0);
    q[i] = static_cast<float>((1.0 - t) * values[low] + t * values[high]);
  }
  return q;
}

// The grid stride that keeps a distribution's samples of a w x h level at most kMaxSamples.
std::uint32_t sample_stride(std::uint32_t width, std::uint32_t height) {
  std::uint32_t stride = 1;
  while (std::size_t{(width + stride - 1) / stride} * ((height + stride - 1) / stride) > kMaxSamples)
    ++stride;
  return stride;
}

template <typename Value, typename F>
std::vector<float> sampled(const std::vector<Value>& field, std::uint32_t width, std::uint32_t height,
                           F&& f) {
  const std::uint32_t stride = sample_stride(width, height);
  std::vector<float> out;
  out.reserve(std::size_t{(width + stride - 1) / stride} * ((height + stride - 1) / stride));
  for (std::uint32_t r = stride / 2; r < height; r += stride)
    for (std::uint32_t c = stride / 2; c < width; c += stride)
      out.push_back(f(field[std::size_t{r} * width + c]));
  return out;
}

double correlation(const std::vector<float>& a, const std::vector<float>& b) {
  const auto n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= n;
  mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 1e-20 && sbb > 1e-20 ? sab / std::sqrt(saa * sbb) : 0.0;
}

double decibels(double energy) {
  return 10.0 * std::log10(energy + 1e-10);
}

std::uint32_t octaves_for(std::uint32_t width, std::uint32_t height, const DistributionOptions& options) {
  const auto fit = static_cast<std::uint32_t>(
                       std::floor(std::log2(std::min(width, height) / static_cast<double>(kCoarsestSide)))) +
                   1;
  return std::max(2u, std::min(options.octaves, fit));
}

double transport(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(static_cast<double>(a[i]) - b[i]);
  return sum / static_cast<double>(a.size());
}

}  // namespace

DistributionStatistics distribution_statistics(std::span<const float> rgb, std::uint32_t width,
                                               std::uint32_t height, const DistributionOptions& options) {
  if (width < 16 || height < 16)
    throw std::invalid_argument("texture statistics: images must be at least 16x16");
  const std::size_t pixels = std::size_t{width} * height;
  if (rgb.size() < pixels * 3) throw std::invalid_argument("texture statistics: image buffer too small");
  std::array<Level, 3> lab;
  for (Level& channel : lab) channel = {width, height, std::vector<float>(pixels)};
  for (std::size_t p = 0; p < pixels; ++p) {
    const auto v = linear_srgb_to_lab(std::max(rgb[p * 3], 0.0f), std::max(rgb[p * 3 + 1], 0.0f),
                                      std::max(rgb[p * 3 + 2], 0.0f));
    for (std::size_t c = 0; c < 3; ++c) lab[c].values[p] = v[c];
  }
  DistributionStatistics s;
  s.octaves = octaves_for(width, height, options);
  for (std::size_t c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (float v : lab[c].values) sum += v;
    s.lab_mean[c] = sum / static_cast<double>(pixels);
    std::vector<float> values = sampled(lab[c].values, width, height, [](float v) { return v; });
    s.lab_quantiles[c] = quantiles_of(values);
  }
  for (std::size_t c = 1; c < 3; ++c) {
    const Pyramid chroma = laplacian_pyramid(lab[c], s.octaves);
    for (const Level& band : chroma.bands) {
      double energy = 0.0;
      for (float v : band.values) energy += double{v} * v;
      energy /= static_cast<double>(band.values.size());
      s.chroma_energy_db.push_back(decibels(energy));
      s.chroma_deviation.push_back(std::sqrt(energy));
    }
  }

  const Pyramid luminance = laplacian_pyramid(lab[0], s.octaves);
  std::vector<std::vector<float>> local_energy(s.octaves);
  for (std::uint32_t o = 0; o < s.octaves; ++o) {
    const Level& band = luminance.bands[o];
    const std::size_t n = band.values.size();
    std::array<std::vector<float>, kOrientations> magnitude;
    std::vector<float> energy(n, 0.f), pooled;
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      const std::vector<Complex> z = oriented_response(band, k);
      double power = 0.0;
      magnitude[k].resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const float m2 = std::norm(z[i]);
        power += m2;
        energy[i] += m2;
        magnitude[k][i] = std::sqrt(m2);
      }
      power /= static_cast<double>(n);
      s.energy_db.push_back(decibels(power));
      // The real part's RMS is sqrt(power / 2): the response at unit RMS.
      const auto unit = static_cast<float>(1.0 / std::sqrt(std::max(power / 2.0, 1e-20)));
      double m2 = 0.0, m3 = 0.0;
      for (const Complex& v : z) {
        const double odd = v.imag();
        m2 += odd * odd;
        m3 += odd * odd * odd;
      }
      m2 /= static_cast<double>(n);
      m3 /= static_cast<double>(n);
      s.odd_skewness.push_back(m2 > 1e-20 ? m3 / (m2 * std::sqrt(m2)) : 0.0);
      const std::vector<float> part =
          sampled(z, band.width, band.height, [unit](Complex v) { return v.real() * unit; });
      pooled.insert(pooled.end(), part.begin(), part.end());
    }
    s.response_quantiles.push_back(quantiles_of(pooled));
    double mean = 0.0;
    for (float& e : energy) mean += (e = std::sqrt(e));
    mean /= static_cast<double>(n);
    const auto inverse = static_cast<float>(1.0 / std::max(mean, 1e-20));
    std::vector<float> normalised =
        sampled(energy, band.width, band.height, [inverse](float v) { return v * inverse; });
    s.energy_quantiles.push_back(quantiles_of(normalised));
    // Adjacent orientations (k, k + 1 cyclically), then orthogonal ones (0-90, 45-135).
    double adjacent = 0.0, orthogonal = 0.0;
    for (std::uint32_t k = 0; k < kOrientations; ++k)
      adjacent += correlation(magnitude[k], magnitude[(k + 1) % kOrientations]) / kOrientations;
    for (std::uint32_t k = 0; k < kOrientations / 2; ++k)
      orthogonal += correlation(magnitude[k], magnitude[k + kOrientations / 2]) / (kOrientations / 2);
    s.cross_orientation.push_back(adjacent);
    s.cross_orientation.push_back(orthogonal);
    local_energy[o] = std::move(energy);
  }
  // Local energy of octave o averaged over 2 x 2 blocks, against octave o + 1 at the same place.
  for (std::uint32_t o = 0; o + 1 < s.octaves; ++o) {
    const Level& fine = luminance.bands[o];
    const Level& coarse = luminance.bands[o + 1];
    std::vector<float> a, b;
    for (std::uint32_t r = 0; r < coarse.height && 2 * r + 1 < fine.height; ++r)
      for (std::uint32_t c = 0; c < coarse.width && 2 * c + 1 < fine.width; ++c) {
        const auto& e = local_energy[o];
        a.push_back(0.25f * (e[std::size_t{2 * r} * fine.width + 2 * c] +
                             e[std::size_t{2 * r} * fine.width + 2 * c + 1] +
                             e[std::size_t{2 * r + 1} * fine.width + 2 * c] +
                             e[std::size_t{2 * r + 1} * fine.width + 2 * c + 1]));
        b.push_back(local_energy[o + 1][std::size_t{r} * coarse.width + c]);
      }
    s.cross_scale.push_back(correlation(a, b));
  }
  return s;
}

DistributionDistance distribution_distance(const DistributionStatistics& a, const DistributionStatistics& b) {
  if (a.octaves != b.octaves || a.energy_db.size() != b.energy_db.size() ||
      a.cross_scale.size() != b.cross_scale.size()) {
    throw std::invalid_argument("texture statistics from different options or image sizes");
  }
  struct Group {
    double sum = 0.0, weight = 0.0;
    double saturation = kSaturation;
    void add(double scaled, double feature_weight = 1.0) {
      const double v = std::min(std::abs(scaled), saturation);
      sum += feature_weight * v * v;
      weight += feature_weight;
    }
    double value() const { return weight > 0.0 ? std::sqrt(sum / weight) : 0.0; }
  };
  const std::size_t octaves = a.octaves;
  std::array<Group, DistributionDistance::kGroups> g;
  g[1].saturation = kEnergySaturation;
  for (std::size_t c = 0; c < 3; ++c)
    g[0].add(transport(a.lab_quantiles[c], b.lab_quantiles[c]) / kColourScale);

  // The eye's contrast sensitivity falls towards the finest octave (periods of 2 to 4 pixels).
  const auto sensitivity = [](std::size_t octave) { return octave == 0 ? 0.35 : octave == 1 ? 0.7 : 1.0; };
  std::vector<double> octave_db_a(octaves), octave_db_b(octaves);
  for (std::size_t o = 0; o < octaves; ++o) {
    double ea = 0.0, eb = 0.0;
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      ea += std::pow(10.0, a.energy_db[o * kOrientations + k] / 10.0) / kOrientations;
      eb += std::pow(10.0, b.energy_db[o * kOrientations + k] / 10.0) / kOrientations;
    }
    octave_db_a[o] = decibels(ea);
    octave_db_b[o] = decibels(eb);
    g[1].add((octave_db_a[o] - octave_db_b[o]) / kEnergyScale, sensitivity(o));
  }
  for (std::size_t i = 0; i < a.chroma_energy_db.size(); ++i) {
    const double visible =
        std::min(1.0, std::max(a.chroma_deviation[i], b.chroma_deviation[i]) / kVisibleChroma);
    g[1].add((a.chroma_energy_db[i] - b.chroma_energy_db[i]) / kChromaEnergyScale,
             visible * sensitivity(i % octaves));
  }
  for (std::size_t o = 0; o < octaves; ++o) {
    g[2].add(transport(a.response_quantiles[o], b.response_quantiles[o]) / kResponseScale, sensitivity(o));
    g[3].add(transport(a.energy_quantiles[o], b.energy_quantiles[o]) / kLocalEnergyScale, sensitivity(o));
    for (std::size_t j = 0; j < 2; ++j)
      g[4].add((a.cross_orientation[2 * o + j] - b.cross_orientation[2 * o + j]) / kCoherenceScale,
               sensitivity(o));
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      const double da = a.energy_db[o * kOrientations + k] - octave_db_a[o],
                   db = b.energy_db[o * kOrientations + k] - octave_db_b[o];
      g[5].add((da - db) / kOrientationScale, sensitivity(o));
      g[5].add(
          (a.odd_skewness[o * kOrientations + k] - b.odd_skewness[o * kOrientations + k]) / kOddSkewnessScale,
          sensitivity(o));
    }
  }
  for (std::size_t i = 0; i < a.cross_scale.size(); ++i)
    g[4].add((a.cross_scale[i] - b.cross_scale[i]) / kCoherenceScale, sensitivity(i));

  double weights = 0.0;
  for (double w : kGroupWeights) weights += w;
  DistributionDistance d;
  for (std::size_t i = 0; i < g.size(); ++i) {
    d.groups[i] = g[i].value();
    d.total += kGroupWeights[i] * d.groups[i] / weights;
  }
  return d;
}

}  // namespace carbtf
