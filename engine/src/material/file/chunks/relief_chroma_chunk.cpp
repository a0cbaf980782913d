// RCHL (1.11, optional): u32 chroma levels: how many mip levels above its brightness the render pass reads
// the relief's chroma (RangeTiles::chroma_levels). Written only when it is not
// kDefaultReliefChromaLevels; absent, that default (how the render pass drew earlier files); an earlier
// reader skips it and reads the chroma at the default level.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kReliefChromaChunk{
    .tag = "RCHL",
    .since_minor = 11,
    .present = [](const Material& m) { return m.range.chroma_levels != kDefaultReliefChromaLevels; },
    .encode = [](const Material& m, ByteWriter& w) { w.u32(m.range.chroma_levels); },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          d.material.range.chroma_levels = r.u32();
          return !r.failed();
        },
};

}  // namespace carbtf::detail
