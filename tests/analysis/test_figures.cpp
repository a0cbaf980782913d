// The report's scatter plot (bench fidelity's mean s against size): every series must stay visible,
// also where two variants build the same model and their points coincide.
#include <catch2/catch.hpp>

#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "carbtf/analysis/report/figures.hpp"

namespace carbtf {
namespace {

std::size_t pixels_of(const Figure& f, const std::array<float, 3>& colour) {
  std::size_t count = 0;
  for (std::size_t p = 0; p + 2 < f.rgb.size(); p += 3) {
    if (f.rgb[p] == colour[0] && f.rgb[p + 1] == colour[1] && f.rgb[p + 2] == colour[2]) ++count;
  }
  return count;
}

TEST_CASE("a scatter point drawn on another leaves the one beneath visible", "[analysis][figures]") {
  const std::array<std::string_view, 3> legend{"a", "b", "c"};
  // Series 0 and 1 at the same place, series 2 apart; the legend swatch of each is 49 pixels.
  const std::vector<ScatterPoint> points{{40.0, 0.3, 0}, {40.0, 0.3, 1}, {10.0, 0.05, 2}};
  const Figure f = scatter_figure(points, "X", "Y", legend);
  const std::size_t swatch = 49;
  const std::size_t first = pixels_of(f, subspace_colour(0)), second = pixels_of(f, subspace_colour(2)),
                    apart = pixels_of(f, subspace_colour(4));
  // A lone point is a disc of radius 3 (29 pixels).
  CHECK(apart == swatch + 29);
  // The first keeps its whole disc; the second is a ring around it, not a disc over it.
  CHECK(first == swatch + 29);
  CHECK(second > swatch + 29);
}

}  // namespace
}  // namespace carbtf
