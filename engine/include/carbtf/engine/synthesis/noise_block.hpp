// The address of a rectangular block of one random field: which field (seed, field id) and where.
// Everything random in synthesis is a pure function of (seed, field id, row, col) (docs/design.md 4.4), so
// a block names its values completely, on the CPU and on the GPU.
#pragma once

#include <cstdint>

namespace carbtf {

// A rectangular block of one field. Rows and columns may be negative (burn-in margins).
struct NoiseBlock {
  std::uint64_t seed = 0;
  std::uint32_t field_id = 0;
  std::int32_t row0 = 0;
  std::int32_t col0 = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

}  // namespace carbtf
