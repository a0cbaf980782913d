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
// Per-pixel sampling noise of a band statistic: a correlation or a skewness measured over n pixels of a
// band scatters by about this over sqrt(n), so two crops of one texture differ by it; the scales below
// grow by it in the coarse octaves, which have few pixels, so that chance there is not read as a change.
constexpr double kCorrelationNoise = 4.0;
constexpr double kSkewnessNoise = 9.0;
constexpr double kResponseNoise = 1.5;
constexpr double kLocalEnergyNoise = 1.6;
constexpr double kLightSideNoise = 3.0;
// The odd response's mean over a band's darkest (or brightest) tenth, in units of its RMS: which side of a
// dark or bright spot is the brighter (a cast shadow lies away from the light, a lit facet faces it).
constexpr double kLightSideScale = 0.1;
// A structure statistic of a level under this many pixels counts in proportion: there it is mostly which
// content (a moss patch, a rock) the crop happened to hold, not how the texture is made (two halves of
// coast_sand_rocks differ by 0.3-0.5 in their correlations of local energy at periods of 32 pixels).
constexpr double kReliablePixels = 2048.0;
constexpr double kGrainScale = 3.0;  // dB of the finest octave's energy over the next one's
// colour, energy, grain, responses, local energy, coherence, orientation, lighting
constexpr std::array<double, DistributionDistance::kGroups> kGroupWeights{1.0, 1.5, 3.0, 2.0,
                                                                          2.0, 1.5, 1.0, 1.5};

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

// Mirrored index (crops are not periodic), for offsets up to the kernel radius.
int mirrored(int i, int n) {
  i = i < 0 ? -i : (i >= n ? 2 * n - 2 - i : i);
  return std::clamp(i, 0, n - 1);
}

// The complex response of `band` to the Gabor filter of orientation k (0, 45, 90, 135 degrees; x right,
// y up), separable as the product of a horizontal and a vertical complex 1D filter. Real and imaginary
// parts in separate planes, the borders mirrored once per row or column: the statistics of a 256^2
// pair stay within the 50 ms that the analysis, which chooses by this measure, can afford.
std::vector<Complex> oriented_response(const Level& band, std::uint32_t k) {
  const double angle = k * std::numbers::pi / kOrientations;
  const auto horizontal = gabor_taps(kGaborFrequency * std::cos(angle));
  const auto vertical = gabor_taps(-kGaborFrequency * std::sin(angle));  // row index grows downwards
  constexpr int taps = 2 * kRadius + 1;
  std::array<float, taps> hr{}, hi{}, vr{}, vi{};
  for (int i = 0; i < taps; ++i) {
    hr[i] = horizontal[i].real();
    hi[i] = horizontal[i].imag();
    vr[i] = vertical[i].real();
    vi[i] = vertical[i].imag();
  }
  const int w = static_cast<int>(band.width), h = static_cast<int>(band.height);
  const std::size_t n = band.values.size();
  std::vector<float> rows_re(n), rows_im(n), padded(static_cast<std::size_t>(w + 2 * kRadius));
  for (int r = 0; r < h; ++r) {
    const float* row = band.values.data() + static_cast<std::size_t>(r) * band.width;
    for (int c = -kRadius; c < w + kRadius; ++c)
      padded[static_cast<std::size_t>(c + kRadius)] = row[mirrored(c, w)];
    float* out_re = rows_re.data() + static_cast<std::size_t>(r) * band.width;
    float* out_im = rows_im.data() + static_cast<std::size_t>(r) * band.width;
    for (int c = 0; c < w; ++c) {
      float re = 0.f, im = 0.f;
      for (int i = 0; i < taps; ++i) {
        const float v = padded[static_cast<std::size_t>(c + i)];
        re += hr[i] * v;
        im += hi[i] * v;
      }
      out_re[c] = re;
      out_im[c] = im;
    }
  }
  std::vector<Complex> out(n);
  std::vector<float> sum_re(static_cast<std::size_t>(w)), sum_im(static_cast<std::size_t>(w));
  for (int r = 0; r < h; ++r) {
    std::fill(sum_re.begin(), sum_re.end(), 0.f);
    std::fill(sum_im.begin(), sum_im.end(), 0.f);
    for (int i = 0; i < taps; ++i) {
      const std::size_t source = static_cast<std::size_t>(mirrored(r + i - kRadius, h)) * band.width;
      const float* in_re = rows_re.data() + source;
      const float* in_im = rows_im.data() + source;
      for (int c = 0; c < w; ++c) {
        sum_re[c] += vr[i] * in_re[c] - vi[i] * in_im[c];
        sum_im[c] += vr[i] * in_im[c] + vi[i] * in_re[c];
      }
    }
    for (int c = 0; c < w; ++c)
      out[static_cast<std::size_t>(r) * band.width + static_cast<std::size_t>(c)] =
          Complex(sum_re[c], sum_im[c]);
  }
  return out;
}

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
    s.band_pixels.push_back(static_cast<double>(n));
    std::array<std::vector<float>, kOrientations> magnitude;
    std::vector<float> energy(n, 0.f), pooled;
    std::vector<float> order = band.values;
    const std::size_t tenth = n / 10;
    std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(tenth), order.end());
    const float dark_below = order[tenth];
    std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n - 1 - tenth), order.end());
    const float bright_above = order[n - 1 - tenth];
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
      double dark = 0.0, bright = 0.0;
      std::size_t dark_count = 0, bright_count = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (band.values[i] <= dark_below) {
          dark += z[i].imag();
          ++dark_count;
        }
        if (band.values[i] >= bright_above) {
          bright += z[i].imag();
          ++bright_count;
        }
      }
      const double odd_rms = std::sqrt(std::max(m2, 1e-20));
      s.dark_side.push_back(dark / static_cast<double>(std::max<std::size_t>(dark_count, 1)) / odd_rms);
      s.bright_side.push_back(bright / static_cast<double>(std::max<std::size_t>(bright_count, 1)) / odd_rms);
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

namespace {

// The L* band energy of an octave over its orientations, in dB.
double octave_energy_db(const DistributionStatistics& s, std::size_t octave) {
  double energy = 0.0;
  for (std::uint32_t k = 0; k < kOrientations; ++k)
    energy += std::pow(10.0, s.energy_db[octave * kOrientations + k] / 10.0) / kOrientations;
  return decibels(energy);
}

// A per-orientation statistic changes sign with the direction along its orientation: its first circular
// harmonic over the orientations (0, 45, 90, 135 degrees) is a vector.
std::array<double, 2> first_harmonic(const std::vector<double>& per_orientation, std::size_t octave) {
  double x = 0.0, y = 0.0;
  for (std::uint32_t k = 0; k < kOrientations; ++k) {
    const double v = per_orientation[octave * kOrientations + k];
    const double angle = k * std::numbers::pi / kOrientations;
    x += v * std::cos(angle) / 2.0;
    y += v * std::sin(angle) / 2.0;
  }
  return {x, y};
}

}  // namespace

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
  const auto reliable = [&](std::size_t octave) {
    return std::min(1.0, std::min(a.band_pixels[octave], b.band_pixels[octave]) / kReliablePixels);
  };
  std::vector<double> octave_db_a(octaves), octave_db_b(octaves);
  for (std::size_t o = 0; o < octaves; ++o) {
    octave_db_a[o] = octave_energy_db(a, o);
    octave_db_b[o] = octave_energy_db(b, o);
    g[1].add((octave_db_a[o] - octave_db_b[o]) / kEnergyScale, sensitivity(o));
  }
  for (std::size_t i = 0; i < a.chroma_energy_db.size(); ++i) {
    const double visible =
        std::min(1.0, std::max(a.chroma_deviation[i], b.chroma_deviation[i]) / kVisibleChroma);
    g[1].add((a.chroma_energy_db[i] - b.chroma_energy_db[i]) / kChromaEnergyScale,
             visible * sensitivity(i % octaves));
  }
  // Grain: fine-scale energy the second image lacks, one-sided (a blur's missing grain is mild, speckle
  // added to a smooth texture is not): the finest octave's energy over the next one's, in dB, for L* and
  // for the visible chroma channels, where the first image's slope is the steeper towards the fine end.
  if (octaves > 1) {
    const auto grain = [&](double slope_a, double slope_b, double weight) {
      g[2].add(std::max(0.0, slope_a - slope_b) / kGrainScale, weight);
    };
    grain(octave_db_a[0] - octave_db_a[1], octave_db_b[0] - octave_db_b[1], 1.0);
    for (std::size_t c = 0; c < 2; ++c) {
      const std::size_t i = c * octaves;
      const double visible =
          std::min(1.0, std::max(a.chroma_deviation[i], b.chroma_deviation[i]) / kVisibleChroma);
      grain(a.chroma_energy_db[i] - a.chroma_energy_db[i + 1],
            b.chroma_energy_db[i] - b.chroma_energy_db[i + 1], visible);
    }
  }
  for (std::size_t o = 0; o < octaves; ++o) {
    const double pixels = std::min(a.band_pixels[o], b.band_pixels[o]);
    const double noise = 1.0 / std::sqrt(pixels);
    const double structure_weight = sensitivity(o) * reliable(o);
    g[3].add(transport(a.response_quantiles[o], b.response_quantiles[o]) /
                 std::hypot(kResponseScale, kResponseNoise * noise),
             structure_weight);
    g[4].add(transport(a.energy_quantiles[o], b.energy_quantiles[o]) /
                 std::hypot(kLocalEnergyScale, kLocalEnergyNoise * noise),
             structure_weight);
    const double corr_scale = std::hypot(kCoherenceScale, kCorrelationNoise * noise);
    const double skew_scale = std::hypot(kOddSkewnessScale, kSkewnessNoise * noise);
    for (std::size_t j = 0; j < 2; ++j)
      g[5].add((a.cross_orientation[2 * o + j] - b.cross_orientation[2 * o + j]) / corr_scale,
               structure_weight);
    for (std::uint32_t k = 0; k < kOrientations; ++k) {
      const double da = a.energy_db[o * kOrientations + k] - octave_db_a[o],
                   db = b.energy_db[o * kOrientations + k] - octave_db_b[o];
      g[6].add((da - db) / kOrientationScale, sensitivity(o));
    }
    // Which way the light comes from: per-orientation statistics of the odd response change sign with
    // the direction along the orientation, so their first circular harmonic is a vector towards the
    // light; a quarter turn or a light from elsewhere turns it.
    const auto harmonic_difference = [&](const std::vector<double>& va, const std::vector<double>& vb) {
      const std::array<double, 2> ha = first_harmonic(va, o), hb = first_harmonic(vb, o);
      return std::hypot(ha[0] - hb[0], ha[1] - hb[1]);
    };
    const double side_scale = std::hypot(kLightSideScale, kLightSideNoise * noise);
    g[7].add(harmonic_difference(a.odd_skewness, b.odd_skewness) / skew_scale, structure_weight);
    g[7].add(harmonic_difference(a.dark_side, b.dark_side) / side_scale, structure_weight);
    g[7].add(harmonic_difference(a.bright_side, b.bright_side) / side_scale, structure_weight);
  }
  for (std::size_t i = 0; i < a.cross_scale.size(); ++i) {
    const double pixels = std::min(a.band_pixels[i + 1], b.band_pixels[i + 1]);
    g[5].add((a.cross_scale[i] - b.cross_scale[i]) /
                 std::hypot(kCoherenceScale, kCorrelationNoise / std::sqrt(pixels)),
             sensitivity(i) * reliable(i + 1));
  }

  double weights = 0.0;
  for (double w : kGroupWeights) weights += w;
  DistributionDistance d;
  for (std::size_t i = 0; i < g.size(); ++i) {
    d.groups[i] = g[i].value();
    d.total += kGroupWeights[i] * d.groups[i] / weights;
  }
  return d;
}

OctaveProfile octave_profile(const DistributionStatistics& s, std::size_t octave) {
  if (octave >= s.octaves) throw std::out_of_range("octave_profile: the statistics hold no such octave");
  OctaveProfile p;
  p.energy_db = octave_energy_db(s, octave);
  for (std::size_t c = 0; c < 2 && (c + 1) * s.octaves <= s.chroma_energy_db.size(); ++c)
    p.chroma_energy_db[c] = s.chroma_energy_db[c * s.octaves + octave];
  p.skewness = first_harmonic(s.odd_skewness, octave);
  p.dark_side = first_harmonic(s.dark_side, octave);
  p.bright_side = first_harmonic(s.bright_side, octave);
  return p;
}

}  // namespace carbtf
