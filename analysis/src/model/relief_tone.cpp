#include "carbtf/analysis/model/relief_tone.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/relief_specular.hpp"
#include "carbtf/engine/material/material.hpp"

namespace carbtf {

namespace {

// The tone's sums over the lights of `view`: sum_l I_l and sum_l m_l relit_l (relief_tone.hpp), for the
// grey image (index 0) and for the red, green and blue channels (1-3), in one pass over the images.
struct ToneSums {
  std::array<Plane, 4> measured, explained;
};

ToneSums tone_sums(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                   double light_z_floor, std::span<const float> horizons, const SpecularLobe& lobe,
                   const char* who) {
  const auto rows = static_cast<Eigen::Index>(dataset.height()),
             cols = static_cast<Eigen::Index>(dataset.width());
  if (range_map.rows() != rows || range_map.cols() != cols)
    throw std::invalid_argument(std::string(who) + ": the range map is not the dataset's size");
  ToneSums sums;
  for (std::size_t k = 0; k < 4; ++k) sums.measured[k] = sums.explained[k] = Plane::Zero(rows, cols);
  std::vector<float> rgb(dataset.pixel_count() * 3);
  std::array<Plane, 4> image;
  image.fill(Plane(rows, cols));
  for (std::uint32_t l = 0; l < dataset.lights().size(); ++l) {
    const LightView pair{l, view};
    if (!dataset.has_image(pair)) continue;
    dataset.linear_rgb(pair, rgb);
    for (Eigen::Index i = 0; i < rows * cols; ++i) {
      const auto p = static_cast<std::size_t>(i);
      for (std::size_t k = 1; k < 4; ++k) image[k](i / cols, i % cols) = rgb[3 * p + k - 1];
      image[0](i / cols, i % cols) = (rgb[3 * p] + rgb[3 * p + 1] + rgb[3 * p + 2]) / 3.0;
    }
    if (lobe.strength > 0.0) {
      const Plane highlight =
          lobe_of(lobe, range_map, dataset.lights()[l].vector(), dataset.views()[view].vector(), horizons);
      for (Plane& channel : image) channel -= highlight;
    }
    const Plane relit = relit_factor(range_map, dataset.lights()[l].vector(), light_z_floor, horizons);
    const double relit_mean = relit.mean();
    if (relit_mean <= 0.0) continue;
    for (std::size_t k = 0; k < 4; ++k) {
      sums.measured[k] += image[k];
      sums.explained[k] += relit * (image[k].mean() / relit_mean);
    }
  }
  return sums;
}

// The tone from one channel's sums (or the grey image's).
Plane tone_of(const Plane& measured, const Plane& explained) {
  if (explained.maxCoeff() <= 0.0) return Plane::Ones(measured.rows(), measured.cols());
  // Where no light reaches a texel by the range map's account, nothing is known about its tone.
  return (explained > 0.0)
      .select(measured / explained.max(1e-30), 1.0)
      .max(kReliefToneFloor)
      .min(kReliefToneCeiling);
}

}  // namespace

Plane relief_tone(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map, double light_z_floor,
                  std::span<const float> horizons, const SpecularLobe& lobe) {
  const ToneSums sums = tone_sums(dataset, view, range_map, light_z_floor, horizons, lobe, "relief_tone");
  return tone_of(sums.measured[0], sums.explained[0]);
}

std::vector<Plane> relief_tone_planes(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                                      double light_z_floor, std::span<const float> horizons,
                                      const SpecularLobe& lobe) {
  const ToneSums sums =
      tone_sums(dataset, view, range_map, light_z_floor, horizons, lobe, "relief_tone_planes");
  std::vector<Plane> planes;
  for (std::size_t k = 1; k < 4; ++k) planes.push_back(tone_of(sums.measured[k], sums.explained[k]));
  return planes;
}

double tone_colour_deviation(std::span<const Plane> planes) {
  if (planes.size() != 3) throw std::invalid_argument("tone_colour_deviation: the tone needs three planes");
  double sum = 0.0;
  for (Eigen::Index i = 0; i < planes[0].size(); ++i) {
    std::array<double, 3> log_tone{};
    for (std::size_t k = 0; k < 3; ++k) log_tone[k] = std::log(std::max(planes[k](i), kReliefToneFloor));
    const double grey = (log_tone[0] + log_tone[1] + log_tone[2]) / 3.0;
    for (double l : log_tone) sum += (l - grey) * (l - grey);
  }
  return std::sqrt(sum / (3.0 * static_cast<double>(std::max<Eigen::Index>(1, planes[0].size()))));
}

Plane band_limited_tone(const Plane& tone) {
  constexpr double side = kToneBandLimitSide, centre = 1.0 - 2.0 * side;
  const Eigen::Index rows = tone.rows(), cols = tone.cols();
  if (rows == 0 || cols == 0) return tone;
  Plane along_rows(rows, cols), out(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      along_rows(r, c) = centre * tone(r, c) + side * (tone(r, std::max<Eigen::Index>(c - 1, 0)) +
                                                       tone(r, std::min(c + 1, cols - 1)));
    }
  }
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      out(r, c) = centre * along_rows(r, c) + side * (along_rows(std::max<Eigen::Index>(r - 1, 0), c) +
                                                      along_rows(std::min(r + 1, rows - 1), c));
    }
  }
  return out;
}

void clamp_remainder(std::vector<Plane>& channels, double k) {
  for (Plane& channel : channels) {
    if (channel.size() == 0) continue;
    std::vector<double> values(static_cast<std::size_t>(channel.size()));
    Eigen::Map<Plane>(values.data(), channel.rows(), channel.cols()) = channel;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    const double median = *middle;
    for (double& v : values) v = std::abs(v - median);
    std::nth_element(values.begin(), middle, values.end());
    const double spread = k * 1.4826 * *middle;
    channel = channel.min(median + spread).max(median - spread);
  }
}

std::array<float, 3> relief_tone_chroma(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                                        double light_z_floor, const Plane& tone,
                                        std::span<const float> horizons, const SpecularLobe& lobe) {
  if (tone.rows() != range_map.rows() || tone.cols() != range_map.cols())
    throw std::invalid_argument("relief_tone_chroma: the tone is not the range map's size");
  const Eigen::Index cols = tone.cols();
  const ToneSums sums =
      tone_sums(dataset, view, range_map, light_z_floor, horizons, lobe, "relief_tone_chroma");
  const auto& measured = sums.measured;
  const auto& explained = sums.explained;
  // The least-squares slope of each channel's tone on the grey tone, over the texels both are known at,
  // and how much of the channels' departure from the grey tone the slopes explain.
  auto own_tone = [&](int k, Eigen::Index r, Eigen::Index c) {
    return std::clamp(measured[k + 1](r, c) / explained[k + 1](r, c), kReliefToneFloor, kReliefToneCeiling);
  };
  std::array<float, 3> chroma{1.0f, 1.0f, 1.0f};
  double as_grey = 0.0, as_coloured = 0.0;
  for (int k = 0; k < 3; ++k) {
    double across = 0.0, grey = 0.0;
    for (Eigen::Index i = 0; i < tone.size(); ++i) {
      const Eigen::Index r = i / cols, c = i % cols;
      if (!(explained[k + 1](r, c) > 0.0)) continue;
      across += (own_tone(k, r, c) - 1.0) * (tone(r, c) - 1.0);
      grey += (tone(r, c) - 1.0) * (tone(r, c) - 1.0);
    }
    if (grey > 0.0 && std::isfinite(across / grey)) {
      chroma[static_cast<std::size_t>(k)] =
          static_cast<float>(std::clamp(across / grey, -double{kMaxToneChroma}, double{kMaxToneChroma}));
    }
    for (Eigen::Index i = 0; i < tone.size(); ++i) {
      const Eigen::Index r = i / cols, c = i % cols;
      if (!(explained[k + 1](r, c) > 0.0)) continue;
      const double own = own_tone(k, r, c);
      const double coloured = 1.0 + chroma[static_cast<std::size_t>(k)] * (tone(r, c) - 1.0);
      as_grey += (own - tone(r, c)) * (own - tone(r, c));
      as_coloured += (own - coloured) * (own - coloured);
    }
  }
  if (!(as_coloured <= (1.0 - kToneChromaExplained) * as_grey)) return {1.0f, 1.0f, 1.0f};
  return chroma;
}

std::vector<Plane> weighted_tone(std::span<const Plane> tone, double weight,
                                 const std::array<float, 3>& chroma) {
  if (tone.size() != 1 && tone.size() != 3)
    throw std::invalid_argument("weighted_tone: a relief tone has one plane or three");
  std::vector<Plane> channels;
  for (std::size_t k = 0; k < 3; ++k) {
    const Plane& plane = tone[tone.size() == 3 ? k : 0];
    channels.push_back((1.0 + weight * (double{chroma[k]} * (plane - 1.0))).max(0.0));
  }
  return channels;
}

void apply_relief(std::span<float> rgb, const std::vector<Plane>& tones, const Plane& relit) {
  const auto pixels = static_cast<std::size_t>(relit.size());
  if (tones.size() != 3 || rgb.size() != pixels * 3 ||
      std::any_of(tones.begin(), tones.end(),
                  [&](const Plane& t) { return t.rows() != relit.rows() || t.cols() != relit.cols(); })) {
    throw std::invalid_argument("apply_relief: the image, the tones and the relit factor differ in size");
  }
  const std::size_t width = static_cast<std::size_t>(relit.cols());
  for (std::size_t p = 0; p < pixels; ++p) {
    const auto r = static_cast<Eigen::Index>(p / width), c = static_cast<Eigen::Index>(p % width);
    for (std::size_t k = 0; k < 3; ++k) rgb[p * 3 + k] *= static_cast<float>(tones[k](r, c) * relit(r, c));
  }
}

void match_render_mean(std::vector<Plane>& smooth, const std::vector<Plane>& measured,
                       const std::vector<Plane>& tones, const Plane& relit) {
  if (smooth.size() != measured.size() || smooth.size() != tones.size())
    throw std::invalid_argument("match_render_mean: channel counts differ");
  double rendered = 0.0, target = 0.0;
  for (std::size_t c = 0; c < smooth.size(); ++c) {
    rendered += smooth[c].mean() * (tones[c] * relit).mean();
    target += measured[c].mean();
  }
  const double gain = target / rendered;
  if (!(rendered > 0.0 && target > 0.0 && std::isfinite(gain))) return;
  for (Plane& channel : smooth) channel *= gain;
}

}  // namespace carbtf
