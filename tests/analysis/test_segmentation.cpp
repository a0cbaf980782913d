// Segmentation of the light x view space: the Lab feature, K-means and the whole segmentation on a
// rendered sample material.
#include <catch2/catch.hpp>

#include <set>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/analysis/segmentation/btf_segmentation.hpp"
#include "carbtf/analysis/segmentation/kmeans.hpp"
#include "carbtf/analysis/segmentation/lab_histogram.hpp"
#include "carbtf/reference/noise.hpp"

#include "test_top_view.hpp"

namespace carbtf {
namespace {

BtfDataset rendered_dataset(const std::string& name, std::uint32_t size) {
  return test::rendered_sample(name, size, 2);
}

}  // namespace

TEST_CASE("Lab conversion and the cumulative histogram feature", "[segmentation]") {
  const auto white = linear_srgb_to_lab(1.0f, 1.0f, 1.0f);
  CHECK(white[0] == Approx(100.0f).margin(1e-3));
  CHECK(white[1] == Approx(0.0f).margin(1e-2));
  CHECK(white[2] == Approx(0.0f).margin(1e-2));
  const auto red = linear_srgb_to_lab(1.0f, 0.0f, 0.0f);  // CIE reference: L 53.24, a 80.09, b 67.20
  CHECK(red[0] == Approx(53.24f).margin(0.05));
  CHECK(red[1] == Approx(80.09f).margin(0.1));
  CHECK(red[2] == Approx(67.20f).margin(0.1));
  const std::vector<float> grey(4 * 4 * 3, 0.18f);
  const std::vector<float> feature = lab_cumulative_histogram(grey, 4, 4, 10);
  REQUIRE(feature.size() == 30u);
  CHECK(feature[9] == 1.0f);  // cumulative: rises to 1
  CHECK(feature[3] == 0.0f);  // L* of 18% grey is about 49.5: bins below 40 are empty
  CHECK(feature[4] == 1.0f);
}

TEST_CASE("k-means finds separated clusters, deterministically for a seed and any thread count",
          "[segmentation]") {
  Eigen::MatrixXd samples(300, 2);
  for (int i = 0; i < 300; ++i) {
    const int blob = i % 3;
    samples(i, 0) = blob * 10.0 + reference::gaussian_noise(3, 0, i, 0);
    samples(i, 1) = (blob == 1 ? 10.0 : 0.0) + reference::gaussian_noise(3, 0, i, 1);
  }
  KMeansOptions options;
  options.clusters = 3;
  options.seed = 42;
  options.threads = 1;
  const KMeansResult one = kmeans(samples, options);
  options.threads = 2;
  const KMeansResult two = kmeans(samples, options);
  REQUIRE(one.labels == two.labels);
  REQUIRE(one.centroids == two.centroids);
  for (int i = 0; i < 300; ++i)
    CHECK(one.labels[static_cast<std::size_t>(i)] == one.labels[static_cast<std::size_t>(i % 3)]);
  CHECK(one.sizes == std::vector<std::uint32_t>{100, 100, 100});
  CHECK(one.nearest == std::vector<std::uint32_t>{one.nearest[0], one.nearest[1], one.nearest[2]});
  CHECK(one.nearest[0] < one.nearest[1]);  // numbered by nearest member
  SECTION("more clusters than distinct samples") {
    options.clusters = 5;
    const KMeansResult few = kmeans(Eigen::MatrixXd::Ones(4, 2), options);
    CHECK(few.centroids.rows() == 1);
    CHECK(few.sizes == std::vector<std::uint32_t>{4});
  }
}

TEST_CASE("segmentation of a sample material is deterministic and separates top from grazing pairs",
          "[segmentation]") {
  const BtfDataset dataset = rendered_dataset("leather", 24);
  SegmentationOptions options;
  options.progress = false;
  options.seed = 9;
  const Segmentation a = segment_btf(dataset, options);
  const Segmentation b = segment_btf(dataset, options);
  REQUIRE(a.index == b.index);
  REQUIRE(a.representatives == b.representatives);
  REQUIRE(a.representatives.size() == 20u);
  REQUIRE(a.index.size() == 81u * 81u);
  // Each representative belongs to its own subspace.
  for (std::size_t s = 0; s < a.representatives.size(); ++s) {
    CHECK(a.index[a.representatives[s].light * 81 + a.representatives[s].view] == s);
  }
  // No subspace holds both a near-top (light, view) pair and a grazing one.
  std::set<int> top, grazing;
  const auto& directions = ubo2003_directions();
  for (std::uint32_t l = 0; l < 81; ++l) {
    for (std::uint32_t v = 0; v < 81; ++v) {
      const double tl = directions[l].theta_degrees(), tv = directions[v].theta_degrees();
      if (tl < 20 && tv < 20) top.insert(a.index[l * 81 + v]);
      if (tl > 70 && tv > 70) grazing.insert(a.index[l * 81 + v]);
    }
  }
  for (int s : top) CHECK(grazing.count(s) == 0);
  // The BTF space spectrum falls steeply: the first eigenvalue dominates.
  REQUIRE(a.eigenvalues.size() == 16u * 16u * 3u);
  CHECK(a.eigenvalues[0] > 10.0 * a.eigenvalues[5]);
  SECTION("another seed is allowed to differ but stays valid") {
    options.seed = 10;
    const Segmentation c = segment_btf(dataset, options);
    CHECK(c.representatives.size() == 20u);
  }
}

}  // namespace carbtf
