#include "carbtf/analysis/segmentation/btf_segmentation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "carbtf/analysis/progress.hpp"
#include "carbtf/analysis/segmentation/kmeans.hpp"
#include "carbtf/analysis/segmentation/lab_histogram.hpp"
#include "carbtf/reference/parallel_for.hpp"

namespace carbtf {
namespace {

// Box-filtered thumbnail of size^2 RGB texels.
std::vector<double> thumbnail(std::span<const float> rgb, std::uint32_t width, std::uint32_t height,
                              std::uint32_t size) {
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
  const Eigen::MatrixXd covariance =
      centred.transpose() * centred / static_cast<double>(std::max<Eigen::Index>(1, thumbnails.rows()));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance, Eigen::EigenvaluesOnly);
  std::vector<double> values(solver.eigenvalues().data(),
                             solver.eigenvalues().data() + solver.eigenvalues().size());
  std::reverse(values.begin(), values.end());
  for (double& v : values) v = std::max(v, 0.0);
  return values;
}

// Each missing pair takes the label of the present pair nearest it, by the light's angle plus the
// view's; of equally near ones, the first in the table's order. Searched outward from the pair over
// lights and views sorted by angle, stopping once no nearer pair can follow: a partial table of
// 1024 x 1024 pairs costs seconds instead of the hours of comparing every missing pair with every
// present one.
void fill_missing_pairs(const BtfDataset& dataset, const std::vector<LightView>& present,
                        const std::vector<std::uint32_t>& labels, Segmentation& result) {
  const std::vector<LightView> missing = dataset.missing_pairs();
  if (missing.empty()) return;
  const std::size_t views = result.views;
  std::vector<std::int64_t> present_at(std::size_t{result.lights} * views, -1);  // index into `present`
  for (std::size_t i = 0; i < present.size(); ++i)
    present_at[present[i].light * views + present[i].view] = static_cast<std::int64_t>(i);
  struct Nearer {
    std::vector<double> angle;         // n x n
    std::vector<std::uint32_t> order;  // per row, the directions by ascending angle
  };
  auto by_angle = [](const std::vector<Direction>& set) {
    const std::size_t n = set.size();
    Nearer t{std::vector<double>(n * n), std::vector<std::uint32_t>(n * n)};
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = 0; b < n; ++b) t.angle[a * n + b] = angle_between(set[a], set[b]);
      const auto row = t.order.begin() + static_cast<std::ptrdiff_t>(a * n);
      std::iota(row, row + static_cast<std::ptrdiff_t>(n), 0u);
      std::stable_sort(row, row + static_cast<std::ptrdiff_t>(n), [&](std::uint32_t x, std::uint32_t y) {
        return t.angle[a * n + x] < t.angle[a * n + y];
      });
    }
    return t;
  };
  const Nearer lights = by_angle(dataset.lights());
  const Nearer view_table = by_angle(dataset.views());
  const std::size_t light_count = dataset.lights().size();
  for (const LightView pair : missing) {
    double best = std::numeric_limits<double>::infinity();
    std::int64_t best_index = -1;
    for (std::size_t k = 0; k < light_count; ++k) {
      const std::uint32_t l = lights.order[pair.light * light_count + k];
      const double light_angle = lights.angle[pair.light * light_count + l];
      if (light_angle > best) break;
      for (std::size_t j = 0; j < views; ++j) {
        const std::uint32_t v = view_table.order[pair.view * views + j];
        const double d = light_angle + view_table.angle[pair.view * views + v];
        if (d > best) break;
        const std::int64_t i = present_at[l * views + v];
        if (i >= 0 && (d < best || i < best_index)) {
          best = d;
          best_index = i;
        }
      }
    }
    result.index[pair.light * views + pair.view] =
        static_cast<std::uint8_t>(labels[static_cast<std::size_t>(best_index)]);
  }
}

}  // namespace

Segmentation segment_btf(const BtfDataset& dataset, const SegmentationOptions& options) {
  if (options.clusters == 0 || options.clusters > 255)
    throw std::invalid_argument("the subspace count K must be within 1..255");
  const std::vector<LightView> present = dataset.present_pairs();
  if (present.empty()) throw std::invalid_argument("the dataset holds no images to segment");
  const std::uint32_t width = dataset.width(), height = dataset.height();
  std::uint32_t stride = 1;
  while (std::size_t{(width + stride - 1) / stride} * ((height + stride - 1) / stride) >
         options.max_feature_pixels)
    ++stride;
  const std::uint32_t thumb = options.spectrum_thumbnail;

  Eigen::MatrixXd features(static_cast<Eigen::Index>(present.size()), 3 * options.bins);
  Eigen::MatrixXd thumbnails(static_cast<Eigen::Index>(present.size()), 3 * thumb * thumb);
  {
    Progress progress("segmentation features", present.size(), options.progress);
    detail::parallel_for(present.size(), options.threads, [&](std::size_t i) {
      std::vector<float> rgb(dataset.pixel_count() * 3);
      dataset.linear_rgb(present[i], rgb);
      const std::vector<float> feature = lab_cumulative_histogram(rgb, width, height, options.bins, stride);
      for (std::size_t f = 0; f < feature.size(); ++f)
        features(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(f)) = feature[f];
      const std::vector<double> small = thumbnail(rgb, width, height, thumb);
      for (std::size_t t = 0; t < small.size(); ++t)
        thumbnails(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(t)) = small[t];
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
    result.index[std::size_t{present[i].light} * result.views + present[i].view] =
        static_cast<std::uint8_t>(clusters.labels[i]);
  }
  fill_missing_pairs(dataset, present, clusters.labels, result);
  for (std::uint32_t member : clusters.nearest) result.representatives.push_back(present[member]);
  result.sizes = clusters.sizes;
  result.inertia = clusters.inertia;
  result.iterations = clusters.iterations;
  result.eigenvalues = spectrum(thumbnails);
  return result;
}

}  // namespace carbtf
