// Materials built in code for render tests: the synthetic CAR models with a bumpy range map.
#pragma once

#include <cmath>
#include <random>

#include "carbtf/analysis/range/range_tile_builder.hpp"
#include "carbtf/analysis/sample/synthetic_material.hpp"

namespace carbtf::test {

// A material with a bumpy range map: the synthetic models plus tiles cut from a smooth random surface.
// `toned`: with a relief tone that follows the relief and a different tone weight per subspace.
inline Material bumpy_material(bool toned = false) {
  Material m = synthetic_material(5, 2);
  Plane heights(48, 48);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> phase(0.0, 6.28);
  const double a = phase(random), b = phase(random);
  for (int r = 0; r < 48; ++r) {
    for (int c = 0; c < 48; ++c)
      heights(r, c) = 2.0 * std::sin(0.4 * c + a) * std::cos(0.3 * r + b) + 0.05 * r;
  }
  RangeTileOptions options;
  options.tile_size = 16;
  if (!toned) {
    m.range = build_range_tiles(heights, options);
    return m;
  }
  const Plane tone = 0.9 + 0.5 * (0.5 * heights).sin();
  m.range = build_range_tiles(heights, options, &tone);
  const float weights[] = {1.0f, 0.0f, 0.5f, 0.25f, 1.0f};
  for (std::size_t s = 0; s < m.subspaces.size(); ++s) m.subspaces[s].tone_weight = weights[s % 5];
  return m;
}

}  // namespace carbtf::test
