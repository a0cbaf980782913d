// Materials built in code for render tests: the synthetic CAR models with a bumpy range map.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "carbtf/reference/synthetic_material.hpp"
#include "test_range_tiles.hpp"

namespace carbtf::test {

// The Bonn UBO2003 database's 81 directions as a material stores them (radians): theta 0, 15, ..., 75
// degrees with 1, 6, 12, 18, 20, 24 azimuths phi = k * 360 / count, by theta, then phi. The analysis
// library's ubo2003_directions() is the same set (the [btf] tests check it); engine tests build without it.
inline std::vector<MaterialDirection> ubo2003_material_directions() {
  constexpr std::uint32_t kAzimuths[] = {1, 6, 12, 18, 20, 24};
  constexpr double kDegree = std::numbers::pi / 180.0;
  std::vector<MaterialDirection> out;
  for (std::uint32_t ring = 0; ring < 6; ++ring) {
    for (std::uint32_t k = 0; k < kAzimuths[ring]; ++k) {
      out.push_back({static_cast<float>((15.0 * ring) * kDegree),
                     static_cast<float>((k * 360.0 / kAzimuths[ring]) * kDegree)});
    }
  }
  return out;
}

// A material with a bumpy range map: the synthetic models plus tiles cut from a smooth random surface.
// `toned`: with a relief tone that follows the relief and a different tone weight per subspace.
inline Material bumpy_material(bool toned = false) {
  Material m = synthetic_material(5, 2);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> phase(0.0, 6.28);
  const double a = phase(random), b = phase(random);
  const auto height = [=](std::uint32_t r, std::uint32_t c) {
    return 2.0 * std::sin(0.4 * c + a) * std::cos(0.3 * r + b) + 0.05 * r;
  };
  const WindowedTileOptions options;
  if (!toned) {
    m.range = windowed_range_tiles(height, {}, options);
    return m;
  }
  m.range = windowed_range_tiles(
      height, [&](std::uint32_t r, std::uint32_t c) { return 0.9 + 0.5 * std::sin(0.5 * height(r, c)); },
      options);
  const float weights[] = {1.0f, 0.0f, 0.5f, 0.25f, 1.0f};
  for (std::size_t s = 0; s < m.subspaces.size(); ++s) m.subspaces[s].tone_weight = weights[s % 5];
  return m;
}

}  // namespace carbtf::test
