// Rendered samples for the analysis tests: a BTF under every UBO2003 light from given views (all of
// them, or the photometric-stereo view), a surface's true heights, and the small analysis the cases fit.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"

namespace carbtf::test {

// The relit factor's floor on the light's z for these datasets: the UBO2003 set's largest theta, 75 degrees.
inline const double kTopViewLightZFloor = std::max(std::cos(75.0 * std::numbers::pi / 180.0), 1e-3);

// `surface` under every UBO2003 light from `views`, held in memory.
inline BtfDataset rendered_dataset(const Surface& surface, const std::vector<Direction>& views) {
  BtfDataset dataset(ubo2003_directions(), views, surface.size, surface.size, ColorEncoding::linear_half);
  RenderOptions render;
  render.progress = false;
  render_btf(surface, dataset.lights(), views, render,
             [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
               dataset.set_linear({l, v}, image);
             });
  return dataset;
}

// The built-in sample `name` (its surface of `seed`) under every UBO2003 light and view, held in memory.
inline BtfDataset rendered_sample(const std::string& name, std::uint32_t size, std::uint64_t seed) {
  return rendered_dataset(make_sample_surface(name, size, seed), ubo2003_directions());
}

// The analysis of a small rendered sample: `clusters` subspaces, range tiles of `tile_size` texels, quiet.
inline AnalysisOptions small_analysis_options(std::uint32_t clusters, std::uint32_t tile_size) {
  AnalysisOptions options;
  options.progress = false;
  options.segmentation.clusters = clusters;
  options.tiles.tile_size = tile_size;
  return options;
}

// The top view of `surface` under every UBO2003 light.
inline BtfDataset top_view_dataset(const Surface& surface) {
  return rendered_dataset(surface, {Direction{}});
}

// The surface's heights in texels, mean zero.
inline Plane heights_of(const Surface& surface) {
  const auto n = static_cast<Eigen::Index>(surface.size);
  Plane heights(n, n);
  for (Eigen::Index i = 0; i < n * n; ++i)
    heights(i / n, i % n) = surface.height[static_cast<std::size_t>(i)];
  return heights - heights.mean();
}

}  // namespace carbtf::test
