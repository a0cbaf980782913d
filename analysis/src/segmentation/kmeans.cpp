#include "carbtf/analysis/segmentation/kmeans.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include "carbtf/reference/parallel_for.hpp"

namespace carbtf {
namespace {

double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double squared_distance(const Eigen::MatrixXd& samples, Eigen::Index i, const Eigen::MatrixXd& centroids,
                        Eigen::Index c) {
  return (samples.row(i) - centroids.row(c)).squaredNorm();
}

// k-means++: the first centre uniformly, each next one with probability proportional to the squared
// distance to the nearest centre chosen so far. Stops early when every sample sits on a centre.
Eigen::MatrixXd seed_centroids(const Eigen::MatrixXd& samples, std::uint32_t clusters, std::mt19937_64& rng) {
  const Eigen::Index n = samples.rows();
  std::vector<Eigen::Index> chosen{
      std::min<Eigen::Index>(n - 1, static_cast<Eigen::Index>(uniform01(rng) * static_cast<double>(n)))};
  std::vector<double> nearest(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i)
    nearest[static_cast<std::size_t>(i)] = (samples.row(i) - samples.row(chosen[0])).squaredNorm();
  while (chosen.size() < clusters) {
    const double total = std::accumulate(nearest.begin(), nearest.end(), 0.0);
    if (!(total > 0.0)) break;
    const double target = uniform01(rng) * total;
    double running = 0.0;
    Eigen::Index pick = -1;
    for (Eigen::Index i = 0; i < n; ++i) {
      running += nearest[static_cast<std::size_t>(i)];
      if (nearest[static_cast<std::size_t>(i)] > 0.0)
        pick = i;  // the last candidate, if rounding leaves target unreached
      if (running > target && nearest[static_cast<std::size_t>(i)] > 0.0) break;
    }
    chosen.push_back(pick);
    for (Eigen::Index i = 0; i < n; ++i) {
      nearest[static_cast<std::size_t>(i)] =
          std::min(nearest[static_cast<std::size_t>(i)], (samples.row(i) - samples.row(pick)).squaredNorm());
    }
  }
  Eigen::MatrixXd centroids(static_cast<Eigen::Index>(chosen.size()), samples.cols());
  for (std::size_t c = 0; c < chosen.size(); ++c)
    centroids.row(static_cast<Eigen::Index>(c)) = samples.row(chosen[c]);
  return centroids;
}

}  // namespace

KMeansResult kmeans(const Eigen::MatrixXd& samples, const KMeansOptions& options) {
  if (samples.rows() == 0 || options.clusters == 0)
    throw std::invalid_argument("k-means needs samples and at least one cluster");
  const Eigen::Index n = samples.rows();
  std::mt19937_64 rng(options.seed);
  Eigen::MatrixXd centroids =
      seed_centroids(samples, static_cast<std::uint32_t>(std::min<Eigen::Index>(options.clusters, n)), rng);
  const Eigen::Index k = centroids.rows();
  std::vector<std::uint32_t> labels(static_cast<std::size_t>(n), std::numeric_limits<std::uint32_t>::max());
  std::vector<double> distances(static_cast<std::size_t>(n));
  KMeansResult result;
  for (result.iterations = 0; result.iterations < options.max_iterations; ++result.iterations) {
    std::atomic<bool> changed{false};
    detail::parallel_for(static_cast<std::size_t>(n), options.threads, [&](std::size_t i) {
      std::uint32_t best = 0;
      double best_distance = std::numeric_limits<double>::infinity();
      for (Eigen::Index c = 0; c < k; ++c) {
        const double d = squared_distance(samples, static_cast<Eigen::Index>(i), centroids, c);
        if (d < best_distance) {
          best_distance = d;
          best = static_cast<std::uint32_t>(c);
        }
      }
      distances[i] = best_distance;
      if (labels[i] != best) {
        labels[i] = best;
        changed = true;
      }
    });
    if (!changed) break;
    Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(k, samples.cols());
    std::vector<std::uint32_t> counts(static_cast<std::size_t>(k), 0);
    for (Eigen::Index i = 0; i < n; ++i) {
      sums.row(labels[static_cast<std::size_t>(i)]) += samples.row(i);
      ++counts[labels[static_cast<std::size_t>(i)]];
    }
    for (Eigen::Index c = 0; c < k; ++c) {
      if (counts[static_cast<std::size_t>(c)] > 0) {
        centroids.row(c) = sums.row(c) / counts[static_cast<std::size_t>(c)];
      } else {
        // An empty cluster restarts at the sample farthest from its centroid.
        const auto far = std::max_element(distances.begin(), distances.end()) - distances.begin();
        centroids.row(c) = samples.row(far);
        distances[static_cast<std::size_t>(far)] = 0.0;
      }
    }
  }
  // Final statistics, and clusters renumbered by their nearest member so the numbering is canonical.
  std::vector<std::uint32_t> nearest(static_cast<std::size_t>(k), 0);
  std::vector<double> nearest_distance(static_cast<std::size_t>(k), std::numeric_limits<double>::infinity());
  result.inertia = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::uint32_t c = labels[static_cast<std::size_t>(i)];
    const double d = squared_distance(samples, i, centroids, c);
    result.inertia += d;
    if (d < nearest_distance[c]) {
      nearest_distance[c] = d;
      nearest[c] = static_cast<std::uint32_t>(i);
    }
  }
  std::vector<std::uint32_t> live;
  for (std::uint32_t c = 0; c < k; ++c) {
    if (std::isfinite(nearest_distance[c])) live.push_back(c);
  }
  std::sort(live.begin(), live.end(),
            [&](std::uint32_t a, std::uint32_t b) { return nearest[a] < nearest[b]; });
  std::vector<std::uint32_t> renumber(static_cast<std::size_t>(k), 0);
  result.centroids.resize(static_cast<Eigen::Index>(live.size()), samples.cols());
  for (std::uint32_t i = 0; i < live.size(); ++i) {
    renumber[live[i]] = i;
    result.centroids.row(i) = centroids.row(live[i]);
    result.nearest.push_back(nearest[live[i]]);
  }
  result.sizes.assign(live.size(), 0);
  result.labels.resize(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < labels.size(); ++i) {
    result.labels[i] = renumber[labels[i]];
    ++result.sizes[result.labels[i]];
  }
  return result;
}

}  // namespace carbtf
