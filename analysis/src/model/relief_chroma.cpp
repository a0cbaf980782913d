#include "carbtf/analysis/model/relief_chroma.hpp"

#include <algorithm>

#include "carbtf/engine/material/material.hpp"

namespace carbtf {

std::uint32_t relief_chroma_levels(std::uint32_t chroma_halvings) {
  if (chroma_halvings == 0) return 0;
  return std::min(chroma_halvings, kMaxReliefChromaLevels - 1) + 1;  // no wrap past the largest count
}

}  // namespace carbtf
