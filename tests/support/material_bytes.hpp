// Crafting hostile material files from valid ones: encode_material() refuses what validation refuses,
// so tests write a valid file with marker values and patch the bytes afterwards, then mend the CRCs so
// the damage reaches the payload checks instead of stopping at the checksum.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "carbtf/engine/material/material_file.hpp"

namespace carbtf::test {

// Recomputes every chunk CRC that the (possibly mutated) chunk sizes let us find.
inline void fix_crcs(std::vector<std::uint8_t>& bytes) {
  std::size_t at = 12;
  auto u32_at = [&](std::size_t p) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t{bytes[p + i]} << (8 * i);
    return v;
  };
  while (at + 8 <= bytes.size()) {
    const std::uint32_t size = u32_at(at + 4);
    if (size > bytes.size() - at - 8 || bytes.size() - at - 8 - size < 4) return;
    const std::uint32_t crc = crc32(std::span(bytes).subspan(at, 8 + size));
    for (int i = 0; i < 4; ++i) bytes[at + 8 + size + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    at += 12 + size;
  }
}

// Replaces every little-endian float32 equal to `marker` by `value`; returns how many were replaced.
inline int replace_float(std::vector<std::uint8_t>& bytes, float marker, float value) {
  std::uint8_t from[4], to[4];
  std::memcpy(from, &marker, 4);
  std::memcpy(to, &value, 4);
  int count = 0;
  for (auto it = bytes.begin(); (it = std::search(it, bytes.end(), from, from + 4)) != bytes.end(); it += 4) {
    std::copy(to, to + 4, it);
    ++count;
  }
  return count;
}

}  // namespace carbtf::test
