// The address of a rectangular block of one random field: which field (seed, field id) and where.
// Everything random in synthesis is a pure function of (seed, field id, row, col) (docs/design.md 4.4), so
// a block names its values completely, on the CPU and on the GPU.
#pragma once

#include <cstdint>

namespace carbtf {

// A rectangular block of one field. Rows and columns may be negative (burn-in margins). The fields are
// addressed in 32 bits: a field is periodic with period 2^32 in rows and columns, and a block's
// coordinates are taken modulo 2^32 (two's complement), on the GPU and the CPU alike. They are 64-bit,
// like every window's in carbtf (texture_window.hpp), so that no caller narrows one on the way.
struct NoiseBlock {
  std::uint64_t seed = 0;
  std::uint32_t field_id = 0;
  std::int64_t row0 = 0;
  std::int64_t col0 = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

}  // namespace carbtf
