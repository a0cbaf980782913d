// The seeded window of the unbounded texture: which texture (the seed) and which rows and columns of it.
// The range map's enlargement (range_tiles.hpp), the subspace images' synthesis (SynthesisBlock,
// synthesis_block.hpp) and the material binding (MaterialBindingInfo) all name their window with it, so
// a host moves one window between them. Coordinates are 64-bit everywhere. The synthesis's pyramid works in
// 32-bit texture coordinates (its random fields repeat every 2^32, noise_block.hpp): a synthesis refuses a
// window whose rows or columns, with their burn-in, lie beyond them (within_texture_coordinates(),
// synthesis_block.hpp); the range map has no such limit.
#pragma once

#include <cstdint>

namespace carbtf {

struct TextureWindow {
  std::uint64_t seed = 0;
  std::int64_t row0 = 0;
  std::int64_t col0 = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  // > 0: the window tiles with period width x height (docs/design.md 4.4): the synthesis covers (width +
  // overlap) x (height + overlap) texels from (row0, col0) and folds the last `overlap` columns and rows
  // onto the first; the range map's tile grid repeats, or its larger map folds around its mean.
  std::uint32_t periodic_overlap = 0;
};

}  // namespace carbtf
