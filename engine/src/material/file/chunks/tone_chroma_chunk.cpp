// TCHR (1.4, optional): f32 tone_chroma[3]: how far each colour channel follows the relief tone.
// Written only when the tone is not grey; absent, all 1 (a grey tone, as earlier files mean); an
// earlier reader skips it.
#include <algorithm>

#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kToneChromaChunk{
    .tag = "TCHR",
    .since_minor = 4,
    .present =
        [](const Material& m) {
          return std::any_of(m.range.tone_chroma.begin(), m.range.tone_chroma.end(),
                             [](float c) { return c != 1.0f; });
        },
    .encode =
        [](const Material& m, ByteWriter& w) {
          for (float c : m.range.tone_chroma) w.f32(c);
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          for (float& c : d.material.range.tone_chroma) c = r.f32();
          return !r.failed();
        },
};

}  // namespace carbtf::detail
