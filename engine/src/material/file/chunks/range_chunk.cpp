// RNGE: the range map as Wang tiles: u32 tile_size, u32 edge_colours, f32 height_offset, f32
// height_scale, u16 patches[2 * colours * size^2], u16 cuts[colours^4 * 4 * size / 2] (tile_size 0:
// none). The patches are rasters for the raster and window filters; the cuts after them are runs of
// small steps, which Sub over u16 turns into 0s and 1s.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

namespace {
constexpr std::uint32_t kRangeHeaderBytes = 16;  // tile size, edge colours, height offset and scale
}

extern const ChunkCodec kRangeChunk{
    .tag = "RNGE",
    .since_minor = 0,
    .required = true,
    .encode =
        [](const Material& m, ByteWriter& w) {
          const RangeTiles& r = m.range;
          w.u32(r.tile_size);
          w.u32(r.edge_colours);
          w.f32(r.height_offset);
          w.f32(r.height_scale);
          for (std::uint16_t v : r.patches) w.u16(v);
          for (std::uint16_t v : r.cuts) w.u16(v);
        },
    // Only the fields it holds: the optional relief chunks may come earlier in the file.
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          RangeTiles& t = d.material.range;
          t.tile_size = r.u32();
          t.edge_colours = r.u32();
          t.height_offset = r.f32();
          t.height_scale = r.f32();
          if (r.failed() || t.tile_size > kMaxTileSize || t.edge_colours > kMaxEdgeColours) return false;
          if (t.tile_size == 0) return true;
          const std::size_t c = t.edge_colours;
          const std::size_t patch_values = 2 * c * t.tile_size * t.tile_size;
          const std::size_t cut_values = c * c * c * c * 4 * (t.tile_size / 2);
          if (!r.can_read(patch_values + cut_values, 2)) return false;
          t.patches.resize(patch_values);
          for (auto& v : t.patches) v = r.u16();
          t.cuts.resize(cut_values);
          for (auto& v : t.cuts) v = r.u16();
          return !r.failed();
        },
    .rasters = [](const Material& m) -> std::optional<RasterLayout> {
      const RangeTiles& r = m.range;
      if (r.tile_size == 0) return std::nullopt;
      return RasterLayout{kRangeHeaderBytes, 2, r.tile_size, r.tile_size, 2 * r.edge_colours, 2};
    },
};

}  // namespace carbtf::detail
