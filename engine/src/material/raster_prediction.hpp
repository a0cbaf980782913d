// The value predictor of the material file's raster filter (format 1.3). Heights and relief tone are
// rasters whose neighbouring texels are close, so the file stores each texel minus a prediction from
// texels already decoded, and deflate codes the small differences. The predictor is LOCO-I's median edge
// detector (JPEG-LS): it picks the left or the upper texel across an edge and the plane through the three
// causal texels elsewhere, which halves the residual entropy of a relief against PNG's Sub filter.
// It lives here because two places must agree on it texel for texel: the file's filter and
// fill_unseen_patch_texels (range_tiles.hpp), which sets texels no tile shows to this prediction so that
// they cost nothing.
#pragma once

#include <algorithm>
#include <cstdint>

namespace carbtf::detail {

inline std::uint32_t median_edge_prediction(std::uint32_t left, std::uint32_t above,
                                            std::uint32_t above_left) {
  const std::uint32_t low = std::min(left, above);
  const std::uint32_t high = std::max(left, above);
  if (above_left >= high) return low;
  if (above_left <= low) return high;
  return left + above - above_left;  // within [low, high] here, so no wrap
}

// The prediction of texel (x, y) of a row-major raster `width` values wide: 0 for the first texel, the
// left texel along the first row, the upper one down the first column, the median edge prediction inside.
template <typename Value>
std::uint32_t raster_prediction(const Value* raster, std::uint32_t width, std::uint32_t x, std::uint32_t y) {
  const std::size_t at = std::size_t{y} * width + x;
  if (y == 0) return x == 0 ? 0u : raster[at - 1];
  if (x == 0) return raster[at - width];
  return median_edge_prediction(raster[at - 1], raster[at - width], raster[at - width - 1]);
}

}  // namespace carbtf::detail
