// The parallax view (analysis/model/parallax_view.hpp): the render's march shown on the CPU, which the
// analysis uses to compare a model image in texture space with a measured image that holds the
// parallax. It has to be the inverse of undo_parallax (deshade.hpp), by which a measured image is brought
// into texture space, in the same frame conventions, or the analysis would score models against a
// measurement shifted the other way.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/parallax_view.hpp"

namespace carbtf {
namespace {

constexpr Eigen::Index kSize = 96;

std::array<double, 3> direction(double theta_degrees, double phi_degrees) {
  const double t = theta_degrees * std::numbers::pi / 180, p = phi_degrees * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// A plane of kSize^2 whose value at (row, col) is f(angle of the row, angle of the column), one period
// over the plane each way.
template <class F>
Plane periodic_plane(F f) {
  Plane plane(kSize, kSize);
  const double w = 2.0 * std::numbers::pi / static_cast<double>(kSize);
  for (Eigen::Index r = 0; r < kSize; ++r)
    for (Eigen::Index c = 0; c < kSize; ++c)
      plane(r, c) = f(w * static_cast<double>(r), w * static_cast<double>(c));
  return plane;
}

// A gentle relief, 2.5 texels from its mean at most and slopes under 0.35, so that at 45 degrees no ridge
// hides anything and the undo is exact up to its bilinear reads.
Plane gentle_relief() {
  return periodic_plane([](double y, double x) {
    return 1.5 * std::sin(2 * x + 0.3) * std::cos(y) + 1.0 * std::cos(3 * y - 0.7);
  });
}

// A texture with detail at every position, a few texels across, so that a shift of a texel shows.
Plane patterned_texture() {
  return periodic_plane([](double y, double x) {
    return 1.0 + 0.4 * std::sin(9 * x + 0.5 * std::sin(7 * y)) + 0.3 * std::cos(11 * y + 0.2 * x);
  });
}

std::vector<float> as_floats(const Plane& plane) {
  std::vector<float> values(static_cast<std::size_t>(plane.size()));
  for (Eigen::Index i = 0; i < plane.size(); ++i)
    values[static_cast<std::size_t>(i)] = static_cast<float>(plane(i / kSize, i % kSize));
  return values;
}

Plane as_plane(const std::vector<float>& values) {
  Plane plane(kSize, kSize);
  for (Eigen::Index i = 0; i < plane.size(); ++i)
    plane(i / kSize, i % kSize) = values[static_cast<std::size_t>(i)];
  return plane;
}

// The RMS difference of a and b away from the border, where clamped reads differ.
double rms_inside(const Plane& a, const Plane& b) {
  const Eigen::Index border = 8, n = kSize - 2 * border;
  return std::sqrt((a.block(border, border, n, n) - b.block(border, border, n, n)).square().mean());
}

}  // namespace

TEST_CASE("the parallax view shows a top view, or a flat relief, texel for texel", "[parallax_view]") {
  const Plane texture = patterned_texture();
  const std::vector<float> values = as_floats(texture);
  const ParallaxView top(gentle_relief(), {0.0, 0.0, 1.0});
  const ParallaxView flat(Plane::Constant(kSize, kSize, 3.0), direction(60, 40));
  REQUIRE(top.size() == values.size());
  REQUIRE(flat.size() == values.size());
  CHECK(top.shown(values, 1) == values);
  CHECK(flat.shown(values, 1) == values);
  // On a grid of pixels it shows those pixels, in order; interleaved channels are read apart.
  const std::vector<std::size_t> pixels{5, 700, 1234};
  const ParallaxView some(gentle_relief(), {0.0, 0.0, 1.0}, pixels);
  std::vector<float> two(values.size() * 2);
  for (std::size_t i = 0; i < values.size(); ++i) two[2 * i] = values[i], two[2 * i + 1] = -values[i];
  const std::vector<float> shown = some.shown(two, 2);
  REQUIRE(shown.size() == 6);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    CHECK(shown[2 * i] == values[pixels[i]]);
    CHECK(shown[2 * i + 1] == -values[pixels[i]]);
  }
}

TEST_CASE("the parallax view puts back the parallax that undo_parallax takes out", "[parallax_view]") {
  const Plane relief = gentle_relief(), texture = patterned_texture();
  for (const double azimuth : {0.0, 130.0}) {
    CAPTURE(azimuth);
    const std::array<double, 3> view = direction(45, azimuth);
    // The texture as the view shows it: a measured image of it.
    const Plane measured = as_plane(ParallaxView(relief, view).shown(as_floats(texture), 1));
    const double shift = rms_inside(measured, texture);
    REQUIRE(shift > 0.1);  // the parallax shows: about a texel of shift over the pattern
    std::vector<Plane> undone{measured};
    undo_parallax(undone, relief, view, kAnalysisParallaxScale);
    CHECK(rms_inside(undone.front(), texture) < 0.25 * shift);
    // The undo in a mirrored frame moves the image further, not back: the test tells the conventions apart.
    std::vector<Plane> mirrored{measured};
    undo_parallax(mirrored, relief, {-view[0], -view[1], view[2]}, kAnalysisParallaxScale);
    CHECK(rms_inside(mirrored.front(), texture) > shift);
  }
}

}  // namespace carbtf
