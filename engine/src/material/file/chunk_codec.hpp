// One row of the material file's chunk table (chunk_table.cpp): everything the writer and the reader
// know of one chunk. Each chunk's codec, with its layout, is a file of chunks/; adding a chunk is a new
// codec file and one row of the table.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "carbtf/engine/material/material.hpp"
#include "material/byte_stream.hpp"
#include "material/file/chunk_filters.hpp"

namespace carbtf::detail {

// A material as its chunks are read, with what a chunk holds for another that may come later.
struct MaterialDecoding {
  Material material;
  std::uint32_t index_lights = 0;  // INDX's own counts, checked against DIRS once both are read
  std::uint32_t index_views = 0;
  std::vector<float> tone_weights;  // TWGT, given to the subspaces once SUBS is read
};

struct ChunkCodec {
  std::string_view tag;
  std::uint16_t since_minor = 0;  // the format 1.x that introduced it
  bool required = false;          // a file without it is refused
  bool deflatable = true;         // SETT stays plain text, readable with a hex viewer
  // Whether the writer writes it for this material (nullptr: always).
  bool (*present)(const Material&) = nullptr;
  void (*encode)(const Material&, ByteWriter&) = nullptr;
  // False on a short or out-of-limit payload.
  bool (*decode)(ByteReader&, MaterialDecoding&) = nullptr;
  // Where its payload holds rasters, for the raster and window filters (nullptr: nowhere).
  std::optional<RasterLayout> (*rasters)(const Material&) = nullptr;
  // Once every chunk is read, for a chunk the file has: a problem, or empty (nullptr: nothing to do).
  std::string (*finish)(MaterialDecoding&) = nullptr;
};

// The u32 lights, u32 views that DIRS, INDX and PGAN begin with; read back bounded.
inline void encode_direction_counts(const Material& m, ByteWriter& w) {
  w.u32(static_cast<std::uint32_t>(m.lights.size()));
  w.u32(static_cast<std::uint32_t>(m.views.size()));
}
inline bool decode_direction_counts(ByteReader& r, std::uint32_t& lights, std::uint32_t& views) {
  lights = r.u32();
  views = r.u32();
  return !r.failed() && lights <= kMaxMaterialDirections && views <= kMaxMaterialDirections;
}

}  // namespace carbtf::detail
