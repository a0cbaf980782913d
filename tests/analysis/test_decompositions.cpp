// Colour PCA and the Gaussian-Laplacian pyramid reconstruct their input (up to double rounding).
#include <catch2/catch.hpp>

#include <cmath>

#include "carbtf/analysis/model/colour_pca.hpp"
#include "carbtf/analysis/model/pyramid.hpp"
#include "carbtf/reference/noise.hpp"

namespace carbtf {
namespace {

Plane noise_plane(Eigen::Index rows, Eigen::Index cols, std::uint32_t field) {
  Plane plane(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index c = 0; c < cols; ++c)
      plane(r, c) =
          reference::gaussian_noise(5, field, static_cast<std::int32_t>(r), static_cast<std::int32_t>(c));
  return plane;
}

double max_abs_difference(const Plane& a, const Plane& b) {
  return (a - b).abs().maxCoeff();
}

}  // namespace

TEST_CASE("colour PCA decorrelates and reconstructs exactly", "[decomposition]") {
  for (int channels : {1, 3, 6}) {
    std::vector<Plane> image;
    const Plane shared = noise_plane(40, 33, 100);
    for (int c = 0; c < channels; ++c)
      image.push_back(0.3 + 0.8 * shared * (c + 1) + 0.2 * noise_plane(40, 33, c));
    const ColourPca pca = fit_colour_pca(image);
    const std::vector<Plane> bands = to_bands(pca, image);
    // Orthonormal basis and uncorrelated bands.
    REQUIRE((pca.basis.transpose() * pca.basis - Eigen::MatrixXd::Identity(channels, channels))
                .cwiseAbs()
                .maxCoeff() < 1e-12);
    for (int i = 0; i < channels; ++i)
      for (int j = 0; j < i; ++j) CHECK(std::abs((bands[i] * bands[j]).mean()) < 1e-10);
    const std::vector<Plane> restored = from_bands(pca, bands);
    for (int c = 0; c < channels; ++c) CHECK(max_abs_difference(restored[c], image[c]) < 1e-12);
  }
  SECTION("grey and constant images have an orthonormal basis too") {
    const Plane grey = noise_plane(16, 16, 7);
    const ColourPca pca = fit_colour_pca({grey, grey, grey});
    const auto restored = from_bands(pca, to_bands(pca, {grey, grey, grey}));
    CHECK(max_abs_difference(restored[1], grey) < 1e-12);
    const Plane flat = Plane::Constant(8, 8, 0.5);
    const ColourPca flat_pca = fit_colour_pca({flat, flat, flat});
    CHECK(max_abs_difference(from_bands(flat_pca, to_bands(flat_pca, {flat, flat, flat}))[2], flat) < 1e-15);
  }
}

TEST_CASE("the Gaussian-Laplacian pyramid collapses back to its image", "[decomposition]") {
  for (auto [rows, cols] : {std::pair{64, 64}, std::pair{37, 50}, std::pair{1, 9}, std::pair{3, 3}}) {
    const Plane image = noise_plane(rows, cols, 9) * 3.0 + 1.0;
    for (int levels : {1, 2, 3}) {
      const auto pyramid = build_laplacian_pyramid(image, levels);
      INFO(rows << "x" << cols << ", " << levels << " levels");
      REQUIRE(!pyramid.empty());
      REQUIRE(pyramid.size() <= static_cast<std::size_t>(levels));
      CHECK(max_abs_difference(collapse_pyramid(pyramid), image) < 1e-12);
      if (levels == 3 && rows >= 8) {
        REQUIRE(pyramid.size() == 3u);
        CHECK(pyramid[1].rows() == (rows + 1) / 2);
        CHECK(pyramid[2].cols() == ((cols + 1) / 2 + 1) / 2);
        // Laplacian levels carry detail with zero mean to within the reduction's border effects.
        CHECK(std::abs(pyramid[0].mean()) < 0.1);
      }
    }
  }
  SECTION("reduce keeps a constant and expand of reduce is smooth") {
    const Plane flat = Plane::Constant(20, 12, 2.5);
    CHECK(max_abs_difference(reduce_plane(flat), Plane::Constant(10, 6, 2.5)) < 1e-14);
    CHECK(max_abs_difference(expand_plane(reduce_plane(flat), 20, 12), flat) < 1e-14);
  }
}

}  // namespace carbtf
