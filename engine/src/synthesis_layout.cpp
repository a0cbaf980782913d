#include "carbtf/engine/synthesis_layout.hpp"

#include <algorithm>
#include <cstdlib>

namespace carbtf {

TextureRegion coarse_support(const TextureRegion& fine) {
  const std::int64_t r0 = floor_half(fine.row0 - 1), r1 = floor_half(fine.row0 + fine.rows + 1) + 1;
  const std::int64_t c0 = floor_half(fine.col0 - 1), c1 = floor_half(fine.col0 + fine.cols + 1) + 1;
  return {r0, c0, r1 - r0, c1 - c0};
}

std::vector<TextureRegion> level_regions(const TextureRegion& block, std::uint32_t levels) {
  std::vector<TextureRegion> regions{block};
  for (std::uint32_t level = 1; level < levels; ++level) regions.push_back(coarse_support(regions.back()));
  return regions;
}

std::uint32_t car_frame_pad(std::span<const CarNeighbour> neighbourhood) {
  int pad = 0;
  for (const CarNeighbour& n : neighbourhood) pad = std::max({pad, -int{n.dr}, std::abs(int{n.dc})});
  return static_cast<std::uint32_t>(pad);
}

std::uint32_t car_wavefront_skew(std::span<const CarNeighbour> neighbourhood) {
  int skew = 1;
  for (const CarNeighbour& n : neighbourhood) {
    if (n.dr >= 0) continue;
    const int up = -int{n.dr};
    const int need = int{n.dc} + 1;  // the step gap a * up must exceed dc
    if (need > 0) skew = std::max(skew, (need + up - 1) / up);
  }
  return static_cast<std::uint32_t>(skew);
}

}  // namespace carbtf
