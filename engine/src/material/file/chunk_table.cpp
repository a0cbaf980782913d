#include "material/file/chunk_table.hpp"

#include <array>
#include <string_view>

namespace carbtf::detail {

// The chunks' codecs, each defined in chunks/ with its layout.
extern const ChunkCodec kSettingsChunk, kDirectionsChunk, kIndexChunk, kSubspacesChunk, kRangeChunk,
    kToneChunk, kToneWeightsChunk, kToneChromaChunk, kFeatherChunk, kShadowsChunk, kPairGainsChunk,
    kSpecularChunk, kReliefChromaChunk, kSpecularViewChunk;

namespace {

// The writer's order. A reader takes the chunks in any order; a new chunk is one more row here.
constexpr std::array<const ChunkCodec*, 14> kMaterialChunks{
    &kSettingsChunk,      // SETT
    &kDirectionsChunk,    // DIRS
    &kIndexChunk,         // INDX
    &kSubspacesChunk,     // SUBS
    &kRangeChunk,         // RNGE
    &kToneChunk,          // TONE (1.1)
    &kToneWeightsChunk,   // TWGT (1.2)
    &kToneChromaChunk,    // TCHR (1.4)
    &kFeatherChunk,       // FTHR (1.6)
    &kShadowsChunk,       // SHDW (1.8)
    &kPairGainsChunk,     // PGAN (1.9)
    &kSpecularChunk,      // SPEC (1.10)
    &kReliefChromaChunk,  // RCHL (1.11)
    &kSpecularViewChunk,  // SPVW (1.12)
};

}  // namespace

std::span<const ChunkCodec* const> material_chunks() {
  return kMaterialChunks;
}

int material_chunk_number(std::span<const std::uint8_t> tag) {
  const std::string_view text(reinterpret_cast<const char*>(tag.data()), tag.size());
  for (std::size_t i = 0; i < kMaterialChunks.size(); ++i) {
    if (kMaterialChunks[i]->tag == text) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace carbtf::detail
