// PGAN (1.9, optional): u32 lights, u32 views, u8 gain code per colour channel (R, G, B planes) and
// (light, view) pair, light-major (Material::pair_gains). Written only when the material has pair gains;
// absent, every gain is 1 (as earlier files mean); an earlier reader skips it and renders each pair at
// its subspace's mean colour. Its planes, smooth over lights and views, are rasters for the raster
// filter; the counts are checked against the directions once every chunk is read (validate_material).
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kPairGainsChunk{
    .tag = "PGAN",
    .since_minor = 9,
    .present = [](const Material& m) { return !m.pair_gains.empty(); },
    .encode =
        [](const Material& m, ByteWriter& w) {
          encode_direction_counts(m, w);
          w.bytes(m.pair_gains);
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          std::uint32_t lights = 0, views = 0;
          if (!decode_direction_counts(r, lights, views)) return false;
          const std::size_t count = 3 * std::size_t{lights} * views;
          if (!r.can_read(count, 1)) return false;
          const auto bytes = r.bytes(count);
          d.material.pair_gains.assign(bytes.begin(), bytes.end());
          return !r.failed();
        },
    .rasters = [](const Material& m) -> std::optional<RasterLayout> {
      return RasterLayout{
          8, 1, static_cast<std::uint32_t>(m.views.size()), static_cast<std::uint32_t>(m.lights.size()),
          3, 0};
    },
};

}  // namespace carbtf::detail
