// TONE (1.1, optional): f32 tone_offset, f32 tone_scale, u32 count, u8 tone[count]: the relief tone per
// patch texel (count = the patches' texel count). A 1.0 reader skips it and renders the smooth texture
// without the crease darkening it carries. From 1.7 the count may be three times that: one plane per
// colour channel (R, G, B); a 1.1-1.6 reader rejects such a file. Its planes are rasters for the
// raster and window filters.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

namespace {
constexpr std::uint32_t kToneHeaderBytes = 12;  // tone offset and scale, count
}

extern const ChunkCodec kToneChunk{
    .tag = "TONE",
    .since_minor = 1,
    .present = [](const Material& m) { return !m.range.tone.empty(); },
    .encode =
        [](const Material& m, ByteWriter& w) {
          const RangeTiles& r = m.range;
          w.f32(r.tone_offset);
          w.f32(r.tone_scale);
          w.u32(static_cast<std::uint32_t>(r.tone.size()));
          w.bytes(r.tone);
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          RangeTiles& t = d.material.range;
          t.tone_offset = r.f32();
          t.tone_scale = r.f32();
          const std::uint32_t count = r.u32();
          constexpr std::size_t kMaxToneTexels =
              3 * 2 * std::size_t{kMaxEdgeColours} * kMaxTileSize * kMaxTileSize;  // three planes
          if (r.failed() || count > kMaxToneTexels || !r.can_read(count, 1)) return false;
          const auto bytes = r.bytes(count);
          t.tone.assign(bytes.begin(), bytes.end());
          return !r.failed();
        },
    .rasters = [](const Material& m) -> std::optional<RasterLayout> {
      const RangeTiles& r = m.range;
      if (r.tile_size == 0) return std::nullopt;
      const auto planes = static_cast<std::uint32_t>(tone_planes(r));
      return RasterLayout{kToneHeaderBytes, 1, r.tile_size, r.tile_size, 2 * r.edge_colours * planes, 0};
    },
};

}  // namespace carbtf::detail
