// TWGT (1.2, optional): u32 count, f32 tone_weight per subspace (count = the subspaces): how much of the
// relief tone each subspace image takes. Written only when a subspace takes less than the whole tone;
// absent, every weight is 1 (as a 1.1 file means); a 1.1 reader skips it and applies the whole tone
// everywhere.
#include <algorithm>

#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kToneWeightsChunk{
    .tag = "TWGT",
    .since_minor = 2,
    .present =
        [](const Material& m) {
          return std::any_of(m.subspaces.begin(), m.subspaces.end(),
                             [](const SubspaceModel& s) { return s.tone_weight != 1.0f; });
        },
    .encode =
        [](const Material& m, ByteWriter& w) {
          w.u32(static_cast<std::uint32_t>(m.subspaces.size()));
          for (const SubspaceModel& s : m.subspaces) w.f32(s.tone_weight);
        },
    // Into the decoding's own list: SUBS may come later in the file.
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          const std::uint32_t count = r.u32();
          if (r.failed() || count > kMaxSubspaces || !r.can_read(count, 4)) return false;
          d.tone_weights.resize(count);
          for (float& w : d.tone_weights) w = r.f32();
          return !r.failed();
        },
    .finish = [](MaterialDecoding& d) -> std::string {
      std::vector<SubspaceModel>& subspaces = d.material.subspaces;
      if (d.tone_weights.size() != subspaces.size()) {
        return "chunk TWGT has " + std::to_string(d.tone_weights.size()) + " tone weights for " +
               std::to_string(subspaces.size()) + " subspaces";
      }
      for (std::size_t s = 0; s < subspaces.size(); ++s) subspaces[s].tone_weight = d.tone_weights[s];
      return {};
    },
};

}  // namespace carbtf::detail
