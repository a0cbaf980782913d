// SETT: the analysis settings, as text: u32 count, then per pair u32 key length, key, u32 value length,
// value. Optional; never deflated.
#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

extern const ChunkCodec kSettingsChunk{
    .tag = "SETT",
    .since_minor = 0,
    .required = false,
    .deflatable = false,
    .encode =
        [](const Material& m, ByteWriter& w) {
          w.u32(static_cast<std::uint32_t>(m.settings.size()));
          for (const auto& [key, value] : m.settings) {
            w.text(key);
            w.text(value);
          }
        },
    .decode =
        [](ByteReader& r, MaterialDecoding& d) {
          const std::uint32_t count = r.u32();
          if (count > kMaxSettings || !r.can_read(count, 8)) return false;
          d.material.settings.resize(count);
          for (auto& [key, value] : d.material.settings) {
            key = r.text(kMaxSettingLength);
            value = r.text(kMaxSettingLength);
          }
          return !r.failed();
        },
};

}  // namespace carbtf::detail
