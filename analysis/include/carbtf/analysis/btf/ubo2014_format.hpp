// The Bonn UBO2014 binary BTF format: one `.btf` file per material, in one of two layouts. This header
// is its spec as carbtf reads and writes it (docs: README "BTF data"); the layout follows the
// University of Bonn's reference reader (btflib). All numbers are little-endian.
//
//   signature          10 bytes: "!DFMF08FCR" (DFMF) or "!BDIF06R2!" (raw, BDI)
//   meta data          u32 size (of this block, itself included), u32 version (1-4),
//                      3 x 80 bytes of text (setup, sensor, light source), f32 pixels per mm,
//                      3 x f32 RGB scale; version > 1: u32 cosine flag (1: the light's cos(theta) is
//                      in the data); version > 2: u32 n + n bytes of XML; version > 3: u32 channels,
//                      each a u32 n + n bytes of name
//   directions         u32 views; per view: f32 theta, f32 phi (radians, polar angle from the normal
//                      and azimuth), u32 lights, lights x (f32 theta, f32 phi). Every view lists the
//                      same lights.
//   DFMF:  u32 width, u32 height, u32 rotations + rotations x 9 f32; u32 components (the most of any
//          channel), i32 colour model, 3 f32 colour mean, 9 f32 colour matrix (row-major); per channel:
//          u8 scalar bytes (2: half, 4: float, 8: double), u32 components, u32 rows, u32 columns,
//          components scalars (singular values; unused: the columns' factor holds them), rows x
//          components (U), columns x components (S x V), both row-major. One of U and S x V has a row
//          per light/view pair (light index fastest), the other a row per texel (x fastest, row 0 at
//          the top); a channel's value is their rows' dot product, then the colour model maps the
//          channels to RGB.
//   BDI:   u32 width, u32 height, u32 scan lines per chunk, u8 compression (0: full, 2: sparse; 1,
//          bzip2, is not read), width x height mask bytes (x fastest; non-zero where the texel is
//          stored), u32 rotations + rotations x 9 f32; then chunks, each a u32 byte count and the
//          half-float ABRDFs of `width x scan lines` stored texels (the last chunk may hold fewer),
//          each ABRDF channel fastest, then light, then view.
//
// carbtf's datasets are photographs: where the file's cosine flag is 0 the values are multiplied by
// cos(theta) of the light, so that shading is in the images as in UBO2003's. Negative values (dark-frame
// subtraction and a truncated factorisation leave a few) read as 0.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace carbtf::ubo2014 {

inline constexpr std::string_view kDfmfSignature = "!DFMF08FCR";
inline constexpr std::string_view kBdiSignature = "!BDIF06R2!";

enum class Layout { bdi, dfmf };

// The colour models of DFMF files (btflib's numbering); carbtf reads all but LAB and the spectral ones.
enum class ColourModel : std::int32_t {
  rgb = 0,
  yuv = 1,
  lab = 2,
  pca = 3,
  ycocg = 4,
  spectral = 5,
  spectral_linear = 6,
  ylog_uv = 9,
  ylog_ulog_vlog = 10,
  ylog_u_div_y_v_div_y = 11,
  rgb_log = 12,
};
// The offset the logarithmic models add before taking the logarithm (btflib's drr_eps).
inline constexpr float kLogOffset = 1e-5f;

// Limits carbtf sets on what a file may declare, checked before anything is allocated.
inline constexpr std::uint32_t kMaxSide = 16384;   // texels per side
inline constexpr std::uint32_t kMaxChannels = 64;  // declared (carbtf reads 3: RGB)
inline constexpr std::uint32_t kMaxRotations = 1u << 20;
// A sparse BDI must store at least this share of its texels (1 in 4): the images are allocated in
// full, so a file of a few stored texels must not ask for gigabytes.
inline constexpr std::uint32_t kMinStoredShareDenominator = 4;

}  // namespace carbtf::ubo2014
