// The relief's chroma level the analysis stores (model/relief_chroma.hpp), from the data's colour resolution.
#include <catch2/catch.hpp>

#include "carbtf/analysis/model/relief_chroma.hpp"
#include "carbtf/engine/material/material.hpp"
#include "test_materials.hpp"

namespace carbtf {

TEST_CASE(
    "the relief's chroma is read at the relief's level for full-resolution colour and coarser for a JPEG's",
    "[relief_chroma]") {
  CHECK(relief_chroma_levels(0) == 0);  // PNG, EXR, UBO2014: the measurement's chroma follows the facets
  CHECK(relief_chroma_levels(1) == 2);  // 4:2:0 JPEG (UBO2003): docs/design.md 4.6's measured best
  CHECK(relief_chroma_levels(2) == 3);
  // Whatever a file claims, the level stays one a material may hold.
  for (const std::uint32_t halvings : {3u, 4u, 1000u, 0xFFFFFFFFu}) {
    CHECK(relief_chroma_levels(halvings) == kMaxReliefChromaLevels);  // subsampled: never back to 0
    Material material = test::bumpy_material();
    material.range.chroma_levels = relief_chroma_levels(halvings);
    CHECK(validate_material(material).ok());
  }
}

}  // namespace carbtf
