// SUBS: the subspace models: u32 count; per subspace u32 light, view, width, height, channels, levels;
// f32 mean[channels]; f32 transform[channels^2]; per band (level-major) u32 flags, f32 mean, f32
// band_std, f32 sigma, u32 neighbours, (i8 dr, i8 dc) per neighbour, f32 gamma per neighbour.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {
namespace {

bool decode_car_band(ByteReader& r, CarBandModel& b) {
  b.flags = r.u32();
  b.mean = r.f32();
  b.band_std = r.f32();
  b.sigma = r.f32();
  const std::uint32_t neighbours = r.u32();
  if (neighbours > kMaxNeighbours || !r.can_read(neighbours, 6)) return false;
  b.neighbourhood.resize(neighbours);
  for (CarNeighbour& n : b.neighbourhood) {
    n.dr = r.i8();
    n.dc = r.i8();
  }
  b.gamma.resize(neighbours);
  for (float& g : b.gamma) g = r.f32();
  return !r.failed();
}

bool decode_subspace_model(ByteReader& r, SubspaceModel& s) {
  s.light = r.u32();
  s.view = r.u32();
  s.width = r.u32();
  s.height = r.u32();
  s.channels = r.u32();
  s.levels = r.u32();
  if (r.failed() || s.channels == 0 || s.channels > kMaxChannels || s.levels == 0 ||
      s.levels > kMaxPyramidLevels)
    return false;
  const std::size_t floats = s.channels + std::size_t{s.channels} * s.channels;
  const std::size_t bands = std::size_t{s.levels} * s.channels;
  if (!r.can_read(floats + bands * 5, 4)) return false;
  s.colour_mean.resize(s.channels);
  for (float& v : s.colour_mean) v = r.f32();
  s.colour_transform.resize(std::size_t{s.channels} * s.channels);
  for (float& v : s.colour_transform) v = r.f32();
  s.bands.resize(bands);
  for (CarBandModel& b : s.bands) {
    if (!decode_car_band(r, b)) return false;
  }
  return true;
}

}  // namespace

extern const ChunkCodec kSubspacesChunk{
    .tag = "SUBS",
    .since_minor = 0,
    .required = true,
    .encode =
        [](const Material& m, ByteWriter& w) {
          w.u32(static_cast<std::uint32_t>(m.subspaces.size()));
          for (const SubspaceModel& s : m.subspaces) {
            for (std::uint32_t v : {s.light, s.view, s.width, s.height, s.channels, s.levels}) w.u32(v);
            for (float v : s.colour_mean) w.f32(v);
            for (float v : s.colour_transform) w.f32(v);
            for (const CarBandModel& b : s.bands) {
              w.u32(b.flags);
              w.f32(b.mean);
              w.f32(b.band_std);
              w.f32(b.sigma);
              w.u32(static_cast<std::uint32_t>(b.neighbourhood.size()));
              for (CarNeighbour n : b.neighbourhood) {
                w.i8(n.dr);
                w.i8(n.dc);
              }
              for (float g : b.gamma) w.f32(g);
            }
          }
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          const std::uint32_t count = r.u32();
          if (count > kMaxSubspaces || !r.can_read(count, 24)) return false;
          d.material.subspaces.resize(count);
          for (SubspaceModel& s : d.material.subspaces) {
            if (!decode_subspace_model(r, s)) return false;
          }
          return !r.failed();
        },
};

}  // namespace carbtf::detail
