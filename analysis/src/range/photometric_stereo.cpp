#include "carbtf/analysis/range/photometric_stereo.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "../btf/image_sources.hpp"
#include "carbtf/reference/parallel_for.hpp"
#include "median.hpp"

namespace carbtf {
namespace {

struct PixelFit {
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double c = 0.0;
  bool ok = false;
};

PixelFit solve(const std::vector<std::array<double, 3>>& lights, const std::vector<double>& grey,
               const std::vector<char>& use, bool ambient) {
  const int unknowns = ambient ? 4 : 3;
  Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
  Eigen::Vector4d atb = Eigen::Vector4d::Zero();
  int count = 0;
  for (std::size_t l = 0; l < lights.size(); ++l) {
    if (!use[l]) continue;
    const Eigen::Vector4d row(lights[l][0], lights[l][1], lights[l][2], ambient ? 1.0 : 0.0);
    ata += row * row.transpose();
    atb += row * grey[l];
    ++count;
  }
  PixelFit fit;
  if (count < unknowns + 1) return fit;
  Eigen::LDLT<Eigen::MatrixXd> ldlt(ata.topLeftCorner(unknowns, unknowns));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      ldlt.vectorD().minCoeff() <= 1e-9 * ldlt.vectorD().maxCoeff())
    return fit;
  const Eigen::VectorXd x = ldlt.solve(atb.head(unknowns));
  fit.b = x.head<3>();
  fit.c = ambient ? x(3) : 0.0;
  fit.ok = fit.b.allFinite() && fit.b.norm() > 0.0;
  return fit;
}

}  // namespace

NormalMap photometric_stereo(const std::vector<std::span<const float>>& images,
                             const std::vector<std::array<double, 3>>& lights, std::uint32_t width,
                             std::uint32_t height, std::span<const std::uint8_t> mask,
                             const std::array<double, 3>& view_direction,
                             const PhotometricStereoOptions& options) {
  if (images.size() != lights.size() || lights.size() < 3)
    throw std::invalid_argument("photometric stereo needs one image per light and at least 3 lights");
  const std::size_t pixels = std::size_t{width} * height;
  for (const auto& image : images) {
    if (image.size() < pixels * 3)
      throw std::invalid_argument("photometric stereo: an image is smaller than width x height");
  }
  if (!mask.empty() && mask.size() != pixels)
    throw std::invalid_argument("photometric stereo: the mask does not match the image size");
  NormalMap map;
  map.width = width;
  map.height = height;
  map.normals.assign(pixels * 3, 0.0f);
  map.albedo.assign(pixels * 3, 0.0f);
  map.valid.assign(pixels, 0);
  map.inliers.assign(pixels, 0);
  const std::size_t count = lights.size();
  const Eigen::Vector3d view = Eigen::Vector3d(view_direction.data()).normalized();
  const double specular_cosine = std::cos(options.specular_cone_degrees * std::numbers::pi / 180.0);
  detail::parallel_for(height, options.threads, [&](std::size_t row) {
    std::vector<double> grey(count);
    std::vector<char> use(count);
    std::vector<double> residuals, ranked;
    for (std::size_t p = row * width; p < (row + 1) * width; ++p) {
      map.normals[p * 3 + 2] = 1.0f;
      if (!mask.empty() && mask[p] == 0) continue;
      double brightest = 0.0;
      for (std::size_t l = 0; l < count; ++l) {
        const float* rgb = images[l].data() + p * 3;
        grey[l] = (double{rgb[0]} + rgb[1] + rgb[2]) / 3.0;
        brightest = std::max(brightest, grey[l]);
      }
      // Start from the middle of the pixel's intensity distribution: the darkest samples are the ones
      // most likely in cast or attached shadow, the brightest the ones most likely specular.
      ranked.assign(grey.begin(), grey.end());
      std::sort(ranked.begin(), ranked.end());
      const double low =
          ranked[static_cast<std::size_t>(options.initial_dark_quantile * static_cast<double>(count - 1))];
      const double high =
          ranked[static_cast<std::size_t>(options.initial_bright_quantile * static_cast<double>(count - 1))];
      for (std::size_t l = 0; l < count; ++l)
        use[l] = grey[l] > options.dark_fraction * brightest && grey[l] >= low && grey[l] <= high;
      bool ambient = options.ambient_term;
      PixelFit fit = solve(lights, grey, use, ambient);
      if (!fit.ok && ambient) fit = solve(lights, grey, use, ambient = false);
      for (int iteration = 0; fit.ok && iteration < options.iterations; ++iteration) {
        const Eigen::Vector3d normal = fit.b.normalized();
        const Eigen::Vector3d mirror = 2.0 * normal.dot(view) * normal - view;
        residuals.clear();
        for (std::size_t l = 0; l < count; ++l) {
          if (use[l])
            residuals.push_back(std::abs(grey[l] - (fit.b.dot(Eigen::Vector3d(lights[l].data())) + fit.c)));
        }
        const double threshold =
            std::max(options.rejection * 1.4826 * detail::median(residuals), 1e-3 * fit.b.norm());
        for (std::size_t l = 0; l < count; ++l) {
          const Eigen::Vector3d light(lights[l].data());
          const double residual = grey[l] - (fit.b.dot(light) + fit.c);
          use[l] = grey[l] > options.dark_fraction * brightest && normal.dot(light) >= options.min_cosine &&
                   mirror.dot(light) <= specular_cosine && std::abs(residual) <= threshold;
        }
        PixelFit refit = solve(lights, grey, use, ambient);
        if (!refit.ok && ambient) refit = solve(lights, grey, use, ambient = false);
        // A refit on too few or one-sided samples can tip the normal below the surface: keep the last.
        if (!refit.ok || refit.b.normalized().dot(view) <= 0.05) break;
        fit = refit;
      }
      if (!fit.ok) continue;
      const Eigen::Vector3d normal = fit.b.normalized();
      const double albedo = fit.b.norm();
      double grey_sum = 0.0;
      std::array<double, 3> colour_sum{};
      int used = 0;
      for (std::size_t l = 0; l < count; ++l) {
        if (!use[l]) continue;
        ++used;
        grey_sum += grey[l];
        for (int k = 0; k < 3; ++k) colour_sum[k] += images[l][p * 3 + k];
      }
      for (int k = 0; k < 3; ++k) {
        map.normals[p * 3 + k] = static_cast<float>(normal(k));
        map.albedo[p * 3 + k] =
            static_cast<float>(grey_sum > 0.0 ? albedo * colour_sum[k] / grey_sum : albedo);
      }
      map.valid[p] = 1;
      map.inliers[p] = static_cast<std::uint16_t>(used);
    }
  });
  return map;
}

std::uint32_t top_view(const BtfDataset& dataset) {
  const auto& views = dataset.views();
  if (views.empty()) throw std::invalid_argument("the dataset has no views");
  return static_cast<std::uint32_t>(
      std::min_element(views.begin(), views.end(),
                       [](const Direction& a, const Direction& b) { return a.theta < b.theta; }) -
      views.begin());
}

NormalMap photometric_stereo(const BtfDataset& dataset, std::uint32_t view,
                             const PhotometricStereoOptions& options) {
  std::vector<std::vector<float>> storage;
  std::vector<std::array<double, 3>> lights;
  for (std::uint32_t light = 0; light < dataset.lights().size(); ++light) {
    if (!dataset.has_image({light, view})) continue;
    storage.emplace_back(dataset.pixel_count() * 3);
    dataset.linear_rgb({light, view}, storage.back());
    lights.push_back(dataset.lights()[light].vector());
  }
  if (lights.size() < 3) {
    const Direction& d = dataset.views()[view];
    throw std::invalid_argument(
        dataset.source + ": photometric stereo needs images of one view under at least 3 lights, but view " +
        std::to_string(view) + " (" + detail::describe_direction(d) + ") has " +
        std::to_string(lights.size()) + "; choose a view with more lights with --stereo-view");
  }
  std::vector<std::span<const float>> images(storage.begin(), storage.end());
  return photometric_stereo(images, lights, dataset.width(), dataset.height(), dataset.mask,
                            dataset.views()[view].vector(), options);
}

std::vector<double> angular_errors_degrees(std::span<const float> normals, std::span<const float> truth,
                                           std::span<const std::uint8_t> valid) {
  if (normals.size() != truth.size() || normals.size() % 3 != 0)
    throw std::invalid_argument("normal maps differ in size");
  std::vector<double> errors;
  for (std::size_t p = 0; p < normals.size() / 3; ++p) {
    if (!valid.empty() && valid[p] == 0) continue;
    const Eigen::Vector3d a(normals[p * 3], normals[p * 3 + 1], normals[p * 3 + 2]);
    const Eigen::Vector3d b(truth[p * 3], truth[p * 3 + 1], truth[p * 3 + 2]);
    const double cosine = std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0);
    errors.push_back(std::acos(cosine) * 180.0 / std::numbers::pi);
  }
  return errors;
}

}  // namespace carbtf
