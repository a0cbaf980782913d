// Materials built in code for render tests: the synthetic CAR models with a bumpy range map.
#pragma once

#include <cmath>
#include <random>

#include "carbtf/analysis/range/range_tile_builder.hpp"
#include "carbtf/analysis/sample/synthetic_material.hpp"

namespace carbtf::test {

// A material with a bumpy range map: the synthetic models plus tiles cut from a smooth random surface.
inline Material bumpy_material() {
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
  m.range = build_range_tiles(heights, options);
  return m;
}

}  // namespace carbtf::test
