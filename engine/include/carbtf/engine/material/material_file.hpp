// The material file (.cbtf): a Material on disk, tens of kilobytes.
//
// Layout, all little-endian:
//   header  "CBTF", u16 major version, u16 minor version, u32 chunk count
//   chunks  4-byte tag, u32 payload size, payload, u32 CRC-32 (IEEE 802.3) of tag, size and payload
// Chunks (each at most once; unknown tags with a valid CRC are skipped, so minor versions can add some):
//   SETT  analysis settings: u32 count, then per pair u32 key length, key, u32 value length, value
//   DIRS  u32 lights, u32 views, then (f32 theta, f32 phi) radians per light, then per view
//   INDX  u32 lights, u32 views, u8 subspace per (light, view), light-major
//   SUBS  u32 count; per subspace u32 light, view, width, height, channels, levels; f32 mean[channels];
//         f32 transform[channels^2]; per band (level-major) u32 flags, f32 mean, f32 band_std,
//         f32 sigma, u32 neighbours, (i8 dr, i8 dc) per neighbour, f32 gamma per neighbour
//   RNGE  u32 tile_size, u32 edge_colours, f32 height_offset, f32 height_scale,
//         u16 patches[2 * colours * size^2], u16 cuts[colours^4 * 4 * size / 2] (tile_size 0: none)
//   DEFL  (1.1) any chunk but SETT deflated: 4-byte inner tag, u32 inner payload size, u8 filter
//         (0 none, s <= 8: each byte minus the one s before, as PNG's Sub; 9, format 1.3: the raster
//         filter, with its parameters, for the heights and tone: residuals of a median edge predictor;
//         10, format 1.5: the window filter, which stores patches cut from overlapping places of one
//         map as that map's texels, once; see material_file.cpp), one zlib stream; the reader bounds the
//         claimed size (64 MiB, and 1100:1 over the stream) and checks the filter's layout before it
//         allocates
//   TONE  (1.1, optional) f32 tone_offset, f32 tone_scale, u32 count, u8 tone[count]: the relief tone
//         per patch texel (count = the patches' texel count). A 1.0 reader skips it and renders the
//         smooth texture without the crease darkening it carries. From 1.7 the count may be three
//         times that: one plane per colour channel (R, G, B); a 1.1-1.6 reader rejects such a file.
//   TWGT  (1.2, optional) u32 count, f32 tone_weight per subspace (count = the subspaces): how much of
//         the relief tone each subspace image takes. Absent, every weight is 1 (as a 1.1 file means);
//         a 1.1 reader skips it and applies the whole tone everywhere.
//   TCHR  (1.4, optional) f32 tone_chroma[3]: how far each colour channel follows the relief tone.
//         Absent, all 1 (a grey tone, as earlier files mean); an earlier reader skips it.
//   FTHR  (1.6, optional) u32 feather: the cuts' cross-fade in texels (RangeTiles::feather). Absent, 0
//         (hard cuts, as earlier files mean); an earlier reader skips it and draws hard cuts.
//   SHDW  (1.8, optional) f32 shadow scale: the relief's cast shadows (RangeTiles::shadow_scale). Absent,
//         0 (no shadows, as earlier files mean); an earlier reader skips it and draws no shadows.
//   PGAN  (1.9, optional) u32 lights, u32 views, u8 gain code per colour channel (R, G, B planes) and
//         (light, view) pair, light-major (Material::pair_gains). Absent, every gain is 1 (as earlier
//         files mean); an earlier reader skips it and renders each pair at its subspace's mean colour.
//   SPEC  (1.10, optional) f32 strength, f32 gloss: the relief's specular lobe (RangeTiles::
//         specular_strength, specular_gloss). Absent, no lobe (as earlier files mean); an earlier reader
//         skips it and draws no highlights.
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
inline constexpr std::uint16_t kMaterialFormatMinor = 10;

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
