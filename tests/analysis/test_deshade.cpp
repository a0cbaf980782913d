// De-shading (analysis/model/deshade.hpp, issue 13 item 3b): the relit factor the analysis divides out
// must be the render pass's, in the conventions of the measured images (x right, y up, row 0 at the
// top), or de-shading would add shading on one axis instead of removing it.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material/material.hpp"
#include "test_top_view.hpp"

namespace carbtf {
namespace {

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= static_cast<double>(a.size());
  mb /= static_cast<double>(b.size());
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

}  // namespace

TEST_CASE("the relit factor of a tilted facet is the render pass's", "[deshade]") {
  Plane ramp(8, 8);
  for (Eigen::Index r = 0; r < 8; ++r)
    for (Eigen::Index c = 0; c < 8; ++c)
      ramp(r, c) = 0.5 * static_cast<double>(c) + 0.25 * static_cast<double>(r);
  // Height rises to the right (dx = 0.5) and downwards (dy = -0.25, y up): N ~ (-0.5, 0.25, 1).
  // relit = a + (1 - a) max(N.L, 0) / max(L.z, floor), a the ambient share.
  const double a = kReliefAmbient;
  const double s = std::sqrt(0.5);
  const Plane factor = relit_factor(ramp, {s, 0.0, s}, 0.2);
  const double expected = a + (1.0 - a) * (-0.5 * s + s) / std::sqrt(0.25 + 0.0625 + 1.0) / s;
  CHECK(factor(4, 4) == Approx(expected).epsilon(1e-12));
  const Plane up = relit_factor(ramp, {0.0, s, s}, 0.2);
  CHECK(up(4, 4) == Approx(a + (1.0 - a) * (0.25 * s + s) / std::sqrt(1.3125) / s).epsilon(1e-12));
  // The denominator is floored; facing away: the ambient share alone, never less.
  CHECK(relit_factor(ramp, {-1.0, 0.0, 0.0}, 0.2)(4, 4) ==
        Approx(a + (1.0 - a) * 0.5 / std::sqrt(1.3125) / 0.2));
  CHECK(relit_factor(ramp, {1.0, 0.0, 0.0}, 0.2)(4, 4) == Approx(a).epsilon(1e-12));
  // A flat facet under any light above the floor stays at 1.
  CHECK(relit_factor(Plane::Zero(8, 8), {s, 0.0, s}, 0.2)(4, 4) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("the relit factor follows the shading of a rendered sample, and dividing it out flattens it",
          "[deshade]") {
  constexpr std::uint32_t size = 64;
  const Surface surface = make_sample_surface("coast_sand_rocks", size, 2);
  Plane height(size, size);
  for (std::uint32_t p = 0; p < size * size; ++p) height(p / size, p % size) = surface.height[p];
  // Lights from +x, +y (image up) and the diagonal: a flipped axis would decorrelate at least one.
  for (const double phi : {0.0, 90.0, 225.0}) {
    const Direction light = Direction::from_degrees(50.0, phi);
    std::vector<float> image;
    RenderOptions options;
    options.progress = false;
    render_btf(surface, {light}, {Direction::from_degrees(0.0, 0.0)}, options,
               [&](std::uint32_t, std::uint32_t, std::span<const float> rgb) {
                 image.assign(rgb.begin(), rgb.end());
               });
    const Plane factor = relit_factor(height, light.vector(), test::kTopViewLightZFloor);
    std::vector<double> shading, relit;
    std::vector<Plane> channels(1, Plane(size, size));
    for (std::uint32_t p = 0; p < size * size; ++p) {
      const double albedo = 0.2126 * surface.albedo[p * 3] + 0.7152 * surface.albedo[p * 3 + 1] +
                            0.0722 * surface.albedo[p * 3 + 2];
      const double luminance = 0.2126 * image[p * 3] + 0.7152 * image[p * 3 + 1] + 0.0722 * image[p * 3 + 2];
      shading.push_back(luminance / std::max(albedo, 1e-3));
      relit.push_back(factor(p / size, p % size));
      channels[0](p / size, p % size) = shading.back();
    }
    const double r = correlation(shading, relit);
    INFO("light azimuth " << phi << ": correlation of rendered shading and relit factor " << r);
    CHECK(r > 0.8);
    // De-shaded, the shading's variation drops (cast shadows and the specular lobe remain).
    auto deviation = [](const Plane& p) { return std::sqrt((p - p.mean()).square().mean()) / p.mean(); };
    const double before = deviation(channels[0]);
    divide_shading(channels, factor, 0.3);
    INFO("relative deviation of the shading before " << before << ", after " << deviation(channels[0]));
    CHECK(deviation(channels[0]) < 0.7 * before);
  }
}

}  // namespace carbtf
