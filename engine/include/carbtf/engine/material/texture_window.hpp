// The seeded window of the unbounded texture: which texture (the seed) and which rows and columns of it.
// The range map's enlargement (range_tiles.hpp), the subspace images' synthesis (SynthesisBlock,
// synthesis_block.hpp) and the material binding (MaterialBindingInfo) all name their window with it, so
// a host moves one window between them. Coordinates are 64-bit everywhere. The synthesis's pyramid works in
// 32-bit texture coordinates (its random fields repeat every 2^32, noise_block.hpp): a synthesis refuses a
// window whose rows or columns, with their burn-in, lie beyond them; the range map has no such limit.
#pragma once

#include <cstdint>
#include <limits>

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

// The synthesis's coordinates: two's complement 32-bit rows and columns.
inline constexpr std::int64_t kMinFieldCoordinate = std::numeric_limits<std::int32_t>::min();
inline constexpr std::int64_t kMaxFieldCoordinate = std::numeric_limits<std::int32_t>::max();

// Whether [first, first + count) lies within them.
constexpr bool within_field_coordinates(std::int64_t first, std::int64_t count) {
  return first >= kMinFieldCoordinate && count >= 0 && first <= kMaxFieldCoordinate - count + 1;
}

}  // namespace carbtf
