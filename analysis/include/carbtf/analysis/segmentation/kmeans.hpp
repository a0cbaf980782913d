// K-means clustering (Lloyd) with k-means++ seeding (Arthur & Vassilvitskii 2007), deterministic for a
// seed: the random draws come from std::mt19937_64 (fully specified by the standard) through our own
// integer-to-double mapping, assignments run in parallel but every sum is taken in a fixed order, so
// the same data and seed give the same clusters on any machine and thread count.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace carbtf {

struct KMeansOptions {
  std::uint32_t clusters = 20;
  std::uint64_t seed = 1;
  std::uint32_t max_iterations = 100;
  unsigned threads = 0;  // 0: all hardware threads
};

struct KMeansResult {
  Eigen::MatrixXd centroids;           // clusters x dimensions
  std::vector<std::uint32_t> labels;   // per sample
  std::vector<std::uint32_t> nearest;  // per cluster: the member nearest its centroid
  std::vector<std::uint32_t> sizes;    // per cluster
  double inertia = 0.0;                // sum of squared distances to the assigned centroids
  std::uint32_t iterations = 0;
};

// `samples` is samples x dimensions. At most min(clusters, number of distinct samples) clusters come
// back; they are numbered by their nearest member's index, ascending.
// Throws std::invalid_argument for no samples or zero clusters.
KMeansResult kmeans(const Eigen::MatrixXd& samples, const KMeansOptions& options);

}  // namespace carbtf
