// DIRS: the measured directions: u32 lights, u32 views, then (f32 theta, f32 phi) radians per light,
// then per view.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kDirectionsChunk{
    .tag = "DIRS",
    .since_minor = 0,
    .required = true,
    .encode =
        [](const Material& m, ByteWriter& w) {
          encode_direction_counts(m, w);
          for (const auto* set : {&m.lights, &m.views}) {
            for (const MaterialDirection& d : *set) {
              w.f32(d.theta);
              w.f32(d.phi);
            }
          }
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          std::uint32_t lights = 0, views = 0;
          if (!decode_direction_counts(r, lights, views) || !r.can_read(std::size_t{lights} + views, 8))
            return false;
          d.material.lights.resize(lights);
          d.material.views.resize(views);
          for (auto* set : {&d.material.lights, &d.material.views}) {
            for (MaterialDirection& direction : *set) {
              direction.theta = r.f32();
              direction.phi = r.f32();
            }
          }
          return !r.failed();
        },
};

}  // namespace carbtf::detail
