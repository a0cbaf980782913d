#include "carbtf/analysis/model/relief_specular.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/engine/render/relief_horizons.hpp"

namespace carbtf {

Plane specular_lobe(const Plane& range_map, const std::array<double, 3>& light,
                    const std::array<double, 3>& view, double gloss, std::span<const float> horizons) {
  const Eigen::Index rows = range_map.rows(), cols = range_map.cols();
  if (!horizons.empty() &&
      horizons.size() != static_cast<std::size_t>(rows * cols) * kReliefHorizonDirections) {
    throw std::invalid_argument("specular_lobe: the horizons are not the range map's");
  }
  std::array<double, 3> half{light[0] + view[0], light[1] + view[1], light[2] + view[2]};
  const double half_length = std::sqrt(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]);
  Plane lobe = Plane::Zero(rows, cols);
  if (!(half_length > 0.0)) return lobe;
  for (double& h : half) h /= half_length;
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      const RangeFacet facet = range_map_facet(range_map, r, c);
      const double n_dot_l = facet.cosine(light), n_dot_h = facet.cosine(half);
      if (n_dot_l <= 0.0 || n_dot_h <= 0.0) continue;
      lobe(r, c) = n_dot_l * std::pow(n_dot_h, gloss);
      if (!horizons.empty()) lobe(r, c) *= horizon_visibility(horizons, r * cols + c, light);
    }
  }
  return lobe;
}

Plane lobe_of(const SpecularLobe& lobe, const Plane& range_map, const std::array<double, 3>& light,
              const std::array<double, 3>& view, std::span<const float> horizons) {
  if (!(lobe.strength > 0.0)) return Plane::Zero(range_map.rows(), range_map.cols());
  const double view_gain =
      specular_view_gain(static_cast<float>(lobe.view_power), static_cast<float>(view[2]));
  return lobe.strength * view_gain * specular_lobe(range_map, light, view, lobe.gloss, horizons);
}

SpecularFit fit_relief_specular(const BtfDataset& dataset, std::uint32_t view, const Plane& range_map,
                                const Plane& tone, double light_z_floor, std::span<const float> horizons) {
  const auto rows = static_cast<Eigen::Index>(dataset.height()),
             cols = static_cast<Eigen::Index>(dataset.width());
  if (range_map.rows() != rows || range_map.cols() != cols || tone.rows() != rows || tone.cols() != cols) {
    throw std::invalid_argument("fit_relief_specular: the range map or the tone is not the dataset's size");
  }
  // Per light: the grey image and the relit relief (the diffuse predictor).
  struct LightImages {
    std::uint32_t light;
    Plane image, diffuse;
  };
  std::vector<LightImages> lights;
  std::vector<float> rgb(dataset.pixel_count() * 3);
  for (std::uint32_t l = 0; l < dataset.lights().size(); ++l) {
    const LightView pair{l, view};
    if (!dataset.has_image(pair)) continue;
    dataset.linear_rgb(pair, rgb);
    Plane image(rows, cols);
    for (Eigen::Index i = 0; i < rows * cols; ++i) {
      const auto p = static_cast<std::size_t>(i);
      image(i / cols, i % cols) = (rgb[3 * p] + rgb[3 * p + 1] + rgb[3 * p + 2]) / 3.0;
    }
    Plane diffuse = relit_factor(range_map, dataset.lights()[l].vector(), light_z_floor, horizons) * tone;
    if (!(image.mean() > 0.0) || !((diffuse * diffuse).sum() > 0.0)) continue;
    lights.push_back({l, std::move(image), std::move(diffuse)});
  }
  SpecularFit fit;
  if (lights.empty()) return fit;
  const auto view_vector = dataset.views()[view].vector();
  // The error of I_l = a_l diffuse_l + k lobe_l, a_l by least squares for the given k.
  auto error_of = [&](double k, const std::vector<Plane>* lobes) {
    double sum = 0.0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const Plane target = lobes ? Plane(lights[i].image - k * (*lobes)[i]) : lights[i].image;
      const double a = (target * lights[i].diffuse).sum() / (lights[i].diffuse * lights[i].diffuse).sum();
      sum += std::sqrt((target - a * lights[i].diffuse).square().mean()) / lights[i].image.mean();
    }
    return sum / static_cast<double>(lights.size());
  };
  fit.error_without = fit.error = error_of(0.0, nullptr);
  for (const double gloss : kSpecularGlosses) {
    std::vector<Plane> lobes;
    lobes.reserve(lights.size());
    double numerator = 0.0, denominator = 0.0;
    for (const LightImages& li : lights) {
      lobes.push_back(
          specular_lobe(range_map, dataset.lights()[li.light].vector(), view_vector, gloss, horizons));
      // The lobe and the image with their projections on the diffuse predictor taken out, so that k is
      // the joint least-squares estimate with every a_l.
      const double dd = (li.diffuse * li.diffuse).sum();
      const Plane lobe_rest = lobes.back() - ((lobes.back() * li.diffuse).sum() / dd) * li.diffuse;
      const Plane image_rest = li.image - ((li.image * li.diffuse).sum() / dd) * li.diffuse;
      numerator += (lobe_rest * image_rest).sum();
      denominator += (lobe_rest * lobe_rest).sum();
    }
    if (!(denominator > 0.0)) continue;
    const double k = numerator / denominator;
    if (!(k > 0.0)) continue;
    const double error = error_of(k, &lobes);
    if (error < fit.error) {
      fit.error = error;
      fit.lobe = {k, gloss};
    }
  }
  if (fit.error > (1.0 - kSpecularFitGain) * fit.error_without) {
    fit.lobe = {};
    fit.error = fit.error_without;
  }
  return fit;
}

std::vector<SpecularFit> fit_relief_specular_with_tone(const BtfDataset& dataset, std::uint32_t view,
                                                       const Plane& range_map, double light_z_floor,
                                                       std::span<const float> horizons) {
  std::vector<SpecularFit> rounds{fit_relief_specular(
      dataset, view, range_map, relief_tone(dataset, view, range_map, light_z_floor, horizons), light_z_floor,
      horizons)};
  for (int round = 0; round < kSpecularToneRounds && rounds.back().lobe.strength > 0.0; ++round) {
    const Plane tone = relief_tone(dataset, view, range_map, light_z_floor, horizons, rounds.back().lobe);
    rounds.push_back(fit_relief_specular(dataset, view, range_map, tone, light_z_floor, horizons));
  }
  return rounds;
}

}  // namespace carbtf
