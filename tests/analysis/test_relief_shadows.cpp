// The relief's cast shadows in the analysis (model/relief_shadows.hpp): fitted to the images of a
// rendered sample, whose renderer casts hard shadows from its true heights, they are kept, and they put
// the lit wall and the dark crease in the measured order; a flat relief gets none.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/relief_shadows.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "test_top_view.hpp"

namespace carbtf {
namespace {

using test::heights_of;
using test::top_view_dataset;

// The skewness of the x derivative of the cube root (the lightness the eye sees) of a grey image.
double x_derivative_skewness(const Plane& grey) {
  std::vector<double> d;
  for (Eigen::Index r = 0; r < grey.rows(); ++r)
    for (Eigen::Index c = 0; c + 1 < grey.cols(); ++c)
      d.push_back(std::cbrt(std::max(grey(r, c + 1), 0.0)) - std::cbrt(std::max(grey(r, c), 0.0)));
  double mean = 0.0;
  for (double v : d) mean += v;
  mean /= static_cast<double>(d.size());
  double m2 = 0.0, m3 = 0.0;
  for (double v : d) {
    m2 += (v - mean) * (v - mean);
    m3 += (v - mean) * (v - mean) * (v - mean);
  }
  m2 /= static_cast<double>(d.size());
  m3 /= static_cast<double>(d.size());
  return m3 / std::pow(m2, 1.5);
}

}  // namespace

TEST_CASE("cast shadows are kept where they explain a shadowed relief, in the measured order",
          "[tone][shadows]") {
  constexpr std::uint32_t size = 64;
  const Surface surface = make_sample_surface("leather", size, 3);
  const BtfDataset dataset = top_view_dataset(surface);
  const Plane heights = heights_of(surface);
  const double z_floor = test::kTopViewLightZFloor;

  const ShadowFit fit = fit_shadow_scale(dataset, 0, heights, z_floor);
  INFO("shadow scale " << fit.scale << ": error " << fit.error << ", without shadows " << fit.error_without);
  CHECK(fit.scale > 0.0);
  CHECK(fit.error <= (1.0 - kShadowFitGain) * fit.error_without);

  // Light at 45 degrees from +x (UBO2003 light 19): the measured image, and relit x tone without and
  // with the shadows, each tone measured as its render would divide it out.
  const std::uint32_t light = 19;
  REQUIRE(dataset.lights()[light].vector()[0] > 0.7);
  std::vector<float> rgb(dataset.pixel_count() * 3);
  dataset.linear_rgb({light, 0}, rgb);
  Plane measured(size, size);
  for (std::size_t p = 0; p < dataset.pixel_count(); ++p)
    measured(static_cast<Eigen::Index>(p / size), static_cast<Eigen::Index>(p % size)) =
        rgb[3 * p] + rgb[3 * p + 1] + rgb[3 * p + 2];
  const std::vector<float> horizons = range_map_horizons(heights, fit.scale);
  const Plane unshadowed = relit_factor(heights, dataset.lights()[light].vector(), z_floor) *
                           relief_tone(dataset, 0, heights, z_floor);
  const Plane shadowed = relit_factor(heights, dataset.lights()[light].vector(), z_floor, horizons) *
                         relief_tone(dataset, 0, heights, z_floor, horizons);
  const double skew_measured = x_derivative_skewness(measured),
               skew_unshadowed = x_derivative_skewness(unshadowed),
               skew_shadowed = x_derivative_skewness(shadowed);
  INFO("x derivative skewness: measured " << skew_measured << ", without shadows " << skew_unshadowed
                                          << ", with " << skew_shadowed);
  CHECK(std::abs(skew_shadowed - skew_measured) < std::abs(skew_unshadowed - skew_measured));
}

TEST_CASE("a flat relief casts no shadows and has no horizons", "[tone][shadows]") {
  constexpr std::uint32_t size = 32;
  Surface surface = make_sample_surface("leather", size, 3);
  for (float& h : surface.height) h = 0.0f;
  const BtfDataset dataset = top_view_dataset(surface);
  const ShadowFit fit = fit_shadow_scale(dataset, 0, Plane::Zero(size, size), 0.26);
  CHECK(fit.scale == 0.0);
  CHECK(fit.error == fit.error_without);
  CHECK(range_map_horizons(Plane::Zero(size, size), 0.0).empty());
  for (float h : range_map_horizons(Plane::Zero(size, size), 1.0)) CHECK(h == 0.0f);
  CHECK_THROWS_AS(fit_shadow_scale(dataset, 0, Plane::Zero(size, size + 1), 0.26), std::invalid_argument);
}

}  // namespace carbtf
