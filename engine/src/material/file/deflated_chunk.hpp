// The DEFL envelope (format 1.1): any chunk but SETT may be stored deflated. Its payload is the inner
// chunk's tag (4 bytes), u32 inner payload size, u8 filter, the filter's parameters (chunk_filters.hpp),
// then one zlib stream of the filtered payload. The reader bounds the claimed size (64 MiB, and 1100:1
// over the stream) and checks the filter's layout before it allocates.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <zlib.h>

#include "material/file/chunk_filters.hpp"

namespace carbtf::detail {

inline constexpr std::string_view kDeflatedTag = "DEFL";

// One zlib deflate stream, reset for each payload: a material's chunks and filters are many small
// payloads, and a fresh stream per payload costs more in allocation than in compression.
class Deflater {
 public:
  Deflater();
  ~Deflater();
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  // `bytes` as one zlib stream into `out`; false if zlib fails.
  bool pack(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out);

 private:
  z_stream stream_{};
  bool ready_ = false;
};

// The DEFL payload for the chunk `tag`: the smallest of the filtered deflations of `payload`, or empty
// when none is smaller than it. `rasters` (optional) is where the payload holds rasters, for the raster
// and window filters.
std::vector<std::uint8_t> deflate_chunk(Deflater& deflater, std::string_view tag,
                                        std::span<const std::uint8_t> payload,
                                        const std::optional<RasterLayout>& rasters);

// Inflates a DEFL payload into its inner tag and payload; false with `problem` set when it is malformed.
bool inflate_chunk(std::span<const std::uint8_t> payload, std::array<std::uint8_t, 4>& tag,
                   std::vector<std::uint8_t>& out, std::string& problem);

}  // namespace carbtf::detail
