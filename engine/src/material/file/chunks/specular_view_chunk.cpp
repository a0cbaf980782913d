// SPVW (1.12, optional): f32 view power: how the relief's specular lobe grows with the view's tilt
// (RangeTiles::specular_view_power). Written only when it is above 0; absent, 0 (the same lobe at every
// view, as the render pass drew earlier files); an earlier reader skips it and draws the top view's lobe at
// every view.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kSpecularViewChunk{
    .tag = "SPVW",
    .since_minor = 12,
    .present = [](const Material& m) { return m.range.specular_view_power > 0.0f; },
    .encode = [](const Material& m, ByteWriter& w) { w.f32(m.range.specular_view_power); },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          d.material.range.specular_view_power = r.f32();
          return !r.failed();
        },
};

}  // namespace carbtf::detail
