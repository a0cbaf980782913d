// The material file (.cbtf): a Material on disk, tens of kilobytes.
//
// Layout, all little-endian:
//   header  "CBTF", u16 major version, u16 minor version, u32 chunk count
//   chunks  4-byte tag, u32 payload size, payload, u32 CRC-32 (IEEE 802.3) of tag, size and payload
// Chunks (each at most once; unknown tags with a valid CRC are skipped, so minor versions can add some):
//   DIRS directions, INDX subspace index, SUBS subspace models, RNGE range tiles; and, optional, SETT
//   analysis settings, TONE relief tone (1.1), TWGT tone weights (1.2), TCHR tone chroma (1.4), FTHR
//   feathered cuts (1.6), SHDW cast shadows (1.8), PGAN pair gains (1.9), SPEC specular lobe (1.10),
//   RCHL the relief's chroma levels (1.11), SPVW the specular lobe's view power (1.12). Each chunk's
//   layout is written at the top of its codec, src/material/file/chunks/<name>_chunk.cpp, and the table
//   of them is src/material/file/chunk_table.cpp. An optional chunk is absent when it would hold its
//   default, so an earlier reader skips it and reads the material without that feature.
//   DEFL  (1.1) any chunk but SETT deflated, through a filter for its rasters (1.3: residuals of a median
//         edge predictor; 1.5: windows of one map stored once): src/material/file/deflated_chunk.hpp and
//         chunk_filters.hpp. The reader bounds the claimed size (64 MiB, and 1100:1 over the stream)
//         and checks the filter's layout before it allocates.
// A reader of major version 1 rejects any other major version. Every count is bounded (material.hpp)
// before anything is allocated, every read is bounds-checked, and the decoded material is validated,
// so a truncated, corrupted or hostile file gives an error, never a crash or an unbounded allocation.
// Thread safety: all functions are reentrant.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "carbtf/engine/material/material.hpp"

namespace carbtf {

inline constexpr std::uint16_t kMaterialFormatMajor = 1;
inline constexpr std::uint16_t kMaterialFormatMinor = 12;

struct MaterialEncoding {
  // Deflate every chunk but SETT where that is smaller (format 1.1). Off, every chunk is stored plain:
  // a file a 1.0 reader can read (without the relief tone) and that a hex viewer or a test can patch.
  bool deflate = true;
};

// Encodes a valid material (check it with validate_material first: an invalid one is refused).
Status encode_material(const Material& material, std::vector<std::uint8_t>& out,
                       const MaterialEncoding& encoding = {});

// Decodes `bytes`; `name` (a path, say) prefixes every error message.
Status decode_material(std::span<const std::uint8_t> bytes, const std::string& name, Material& out);

// Reads and decodes a file; writes a file (through a temporary, so a failure leaves no partial file).
Status read_material_file(const std::string& path, Material& out);
// The file's bytes, unchecked (with the same size limit and errors), for callers that also list chunks.
Status read_material_file_bytes(const std::string& path, std::vector<std::uint8_t>& bytes);
// Whole or not at all, and never over what is not a regular file (write_file_whole(), file_output.hpp).
Status write_material_file(const std::string& path, const Material& material);

// One chunk of an encoded material, for size breakdowns (`carbtf info material.cbtf`).
struct MaterialChunkInfo {
  std::string tag;
  std::uint64_t total_bytes = 0;  // header, payload and CRC
  bool known = false;
  std::uint64_t inflated_bytes =
      0;  // for a deflated chunk (listed under its inner tag): its size stored plain; else 0
};
// Lists the chunks of a file that decode_material accepts (call it after a successful decode).
Status list_material_chunks(std::span<const std::uint8_t> bytes, std::vector<MaterialChunkInfo>& out);

// CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of `bytes`, continuing from `crc`.
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace carbtf
