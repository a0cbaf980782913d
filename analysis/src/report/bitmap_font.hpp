// Internal: a 5x7 bitmap font for labelling figures (no font library is among the dependencies).
// Digits, upper-case letters (lower case is drawn upper case) and . , - + / : ( ) % = _ and space.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace carbtf::detail {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = 6;  // one blank column between glyphs

// Rows top to bottom, bit 4 the leftmost column; all zero for a character the font lacks.
std::array<std::uint8_t, kGlyphHeight> glyph_rows(char c);

// Calls plot(x, y) for every lit pixel of `text` drawn from its top-left corner at `scale`.
template <typename Plot>
void rasterize_text(std::string_view text, int x, int y, int scale, Plot&& plot) {
  for (char c : text) {
    const auto rows = glyph_rows(c);
    for (int r = 0; r < kGlyphHeight; ++r) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (!(rows[static_cast<std::size_t>(r)] & (1u << (kGlyphWidth - 1 - col)))) continue;
        for (int sy = 0; sy < scale; ++sy)
          for (int sx = 0; sx < scale; ++sx) plot(x + col * scale + sx, y + r * scale + sy);
      }
    }
    x += kGlyphAdvance * scale;
  }
}

inline int text_width(std::string_view text, int scale) {
  return static_cast<int>(text.size()) * kGlyphAdvance * scale;
}

}  // namespace carbtf::detail
