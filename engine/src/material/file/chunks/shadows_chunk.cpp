// SHDW (1.8, optional): f32 shadow scale: the relief's cast shadows (RangeTiles::shadow_scale). Written
// only when the relief casts shadows; absent, 0 (no shadows, as earlier files mean); an earlier reader
// skips it and draws no shadows.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kShadowsChunk{
    .tag = "SHDW",
    .since_minor = 8,
    .present = [](const Material& m) { return m.range.shadow_scale > 0.0f; },
    .encode = [](const Material& m, ByteWriter& w) { w.f32(m.range.shadow_scale); },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          d.material.range.shadow_scale = r.f32();
          return !r.failed();
        },
};

}  // namespace carbtf::detail
