// INDX: which subspace models each (light, view) pair: u32 lights, u32 views, u8 subspace per pair,
// light-major. Its counts must be DIRS's.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kIndexChunk{
    .tag = "INDX",
    .since_minor = 0,
    .required = true,
    .encode =
        [](const Material& m, ByteWriter& w) {
          encode_direction_counts(m, w);
          w.bytes(m.subspace_index);
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          if (!decode_direction_counts(r, d.index_lights, d.index_views)) return false;
          const auto table = r.bytes(std::size_t{d.index_lights} * d.index_views);
          d.material.subspace_index.assign(table.begin(), table.end());
          return !r.failed();
        },
    .finish = [](MaterialDecoding& d) -> std::string {
      const Material& m = d.material;
      if (d.index_lights == m.lights.size() && d.index_views == m.views.size()) return {};
      return "the index table is " + std::to_string(d.index_lights) + " x " + std::to_string(d.index_views) +
             " but there are " + std::to_string(m.lights.size()) + " lights and " +
             std::to_string(m.views.size()) + " views";
    },
};

}  // namespace carbtf::detail
