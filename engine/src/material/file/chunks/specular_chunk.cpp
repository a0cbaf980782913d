// SPEC (1.10, optional): f32 strength, f32 gloss: the relief's specular lobe (RangeTiles::
// specular_strength, specular_gloss). Written only when the relief has a lobe; absent, no lobe (as
// earlier files mean); an earlier reader skips it and draws no highlights.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kSpecularChunk{
    .tag = "SPEC",
    .since_minor = 10,
    .present = [](const Material& m) { return m.range.specular_strength > 0.0f; },
    .encode =
        [](const Material& m, ByteWriter& w) {
          w.f32(m.range.specular_strength);
          w.f32(m.range.specular_gloss);
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          d.material.range.specular_strength = r.f32();
          d.material.range.specular_gloss = r.f32();
          return !r.failed();
        },
};

}  // namespace carbtf::detail
