// How coarse the render pass reads the relief's chroma (RangeTiles::chroma_levels), from the measured
// images' own colour resolution (BtfDataset::chroma_halvings).
//
// The model's relief modulates the colour's brightness at the finest periods: its creases and facets
// light and darken a texel. A measurement whose colour has less resolution than its brightness (a JPEG's
// 4:2:0 chroma) shows those periods in brightness alone, and a relief whose chroma followed them adds a
// chroma grain the measurement lacks; a measurement with full-resolution colour keeps it.
#pragma once

#include <cstdint>

namespace carbtf {

// 0 for full-resolution colour; for colour halved n times, n + 1: the JPEG's quantisation of its
// already halved chroma takes about one octave more (measured, docs/design.md 4.6: the same leather as
// JPEG and as PNG; as JPEG, leather and coast_sand_rocks nearest at 2 levels, fabric the same within
// 0.001 from 1 to 3). At most kMaxReliefChromaLevels.
std::uint32_t relief_chroma_levels(std::uint32_t chroma_halvings);

}  // namespace carbtf
