#include "carbtf/analysis/segmentation/btf_segmentation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "carbtf/reference/parallel_for.hpp"
#include "carbtf/analysis/progress.hpp"
#include "carbtf/analysis/segmentation/kmeans.hpp"
#include "carbtf/analysis/segmentation/lab_histogram.hpp"

namespace carbtf {
namespace {

// Box-filtered thumbnail of size^2 RGB texels.
std::vector<double> thumbnail(std::span<const float> rgb, std::uint32_t width, std::uint32_t height, std::uint32_t size) {
  std::vector<double> out(std::size_t{size} * size * 3, 0.0);
  std::vector<double> counts(std::size_t{size} * size, 0.0);
  for (std::uint32_t row = 0; row < height; ++row) {
    const std::uint32_t ty = row * size / height;
    for (std::uint32_t col = 0; col < width; ++col) {
      const std::uint32_t tx = col * size / width;
      const std::size_t t = std::size_t{ty} * size + tx;
      for (int k = 0; k < 3; ++k) out[t * 3 + k] += rgb[(std::size_t{row} * width + col) * 3 + k];
      counts[t] += 1.0;
    }
  }
  for (std::size_t t = 0; t < counts.size(); ++t) {
    for (int k = 0; k < 3; ++k) out[t * 3 + k] /= std::max(counts[t], 1.0);
  }
  return out;
}

std::vector<double> spectrum(const Eigen::MatrixXd& thumbnails) {
  const Eigen::MatrixXd centred = thumbnails.rowwise() - thumbnails.colwise().mean();
  const Eigen::MatrixXd covariance = centred.transpose() * centred / static_cast<double>(std::max<Eigen::Index>(1, thumbnails.rows()));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance, Eigen::EigenvaluesOnly);
  std::vector<double> values(solver.eigenvalues().data(), solver.eigenvalues().data() + solver.eigenvalues().size());
  std::reverse(values.begin(), values.end());
  for (double& v : values) v = std::max(v, 0.0);
  return values;
}

}  // namespace

Segmentation segment_btf(const BtfDataset& dataset, const SegmentationOptions& options) {
  if (options.clusters == 0 || options.clusters > 255) throw std::invalid_argument("the subspace count K must be within 1..255");
  const std::vector<LightView> present = dataset.present_pairs();
  if (present.empty()) throw std::invalid_argument("the dataset holds no images to segment");
  const std::uint32_t width = dataset.width(), height = dataset.height();
  std::uint32_t stride = 1;
  while (std::size_t{(width + stride - 1) / stride} * ((height + stride - 1) / stride) > options.max_feature_pixels) ++stride;
  const std::uint32_t thumb = options.spectrum_thumbnail;

  Eigen::MatrixXd features(static_cast<Eigen::Index>(present.size()), 3 * options.bins);
  Eigen::MatrixXd thumbnails(static_cast<Eigen::Index>(present.size()), 3 * thumb * thumb);
  {
  Progress progress("segmentation features", present.size(), options.progress);
  detail::parallel_for(present.size(), options.threads, [&](std::size_t i) {
    std::vector<float> rgb(dataset.pixel_count() * 3);
    dataset.linear_rgb(present[i], rgb);
    const std::vector<float> feature = lab_cumulative_histogram(rgb, width, height, options.bins, stride);
    for (std::size_t f = 0; f < feature.size(); ++f) features(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(f)) = feature[f];
    const std::vector<double> small = thumbnail(rgb, width, height, thumb);
    for (std::size_t t = 0; t < small.size(); ++t) thumbnails(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(t)) = small[t];
    progress.advance();
  });
  }

  KMeansOptions kmeans_options;
  kmeans_options.clusters = options.clusters;
  kmeans_options.seed = options.seed;
  kmeans_options.threads = options.threads;
  const KMeansResult clusters = kmeans(features, kmeans_options);

  Segmentation result;
  result.lights = static_cast<std::uint32_t>(dataset.lights().size());
  result.views = static_cast<std::uint32_t>(dataset.views().size());
  result.index.assign(std::size_t{result.lights} * result.views, 0);
  for (std::size_t i = 0; i < present.size(); ++i) {
    result.index[std::size_t{present[i].light} * result.views + present[i].view] = static_cast<std::uint8_t>(clusters.labels[i]);
  }
  for (const LightView missing : dataset.missing_pairs()) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < present.size(); ++i) {
      const double d = angle_between(dataset.lights()[missing.light], dataset.lights()[present[i].light]) +
                       angle_between(dataset.views()[missing.view], dataset.views()[present[i].view]);
      if (d < best) {
        best = d;
        result.index[std::size_t{missing.light} * result.views + missing.view] = static_cast<std::uint8_t>(clusters.labels[i]);
      }
    }
  }
  for (std::uint32_t member : clusters.nearest) result.representatives.push_back(present[member]);
  result.sizes = clusters.sizes;
  result.inertia = clusters.inertia;
  result.iterations = clusters.iterations;
  result.eigenvalues = spectrum(thumbnails);
  return result;
}

}  // namespace carbtf
