// FTHR (1.6, optional): u32 feather: the cuts' cross-fade in texels (RangeTiles::feather). Written only
// for feathered cuts; absent, 0 (hard cuts, as earlier files mean); an earlier reader skips it and draws
// hard cuts.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kFeatherChunk{
    .tag = "FTHR",
    .since_minor = 6,
    .present = [](const Material& m) { return m.range.feather > 0; },
    .encode = [](const Material& m, ByteWriter& w) { w.u32(m.range.feather); },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          d.material.range.feather = r.u32();
          return !r.failed();
        },
};

}  // namespace carbtf::detail
