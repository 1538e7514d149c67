// A tiny built-in 5x7 bitmap font (printable ASCII) for the viewer's HUD
// and teleop's keyboard window, so neither needs font files. Glyphs sit in 6x8 cells (one column and one
// row of spacing).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace simpartner {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kCellWidth = 6;
inline constexpr int kCellHeight = 8;
inline constexpr char kFirstGlyph = ' ';
inline constexpr char kLastGlyph = '~';

// Rows top to bottom; bit 4 is the leftmost column. Characters outside
// ' '..'~' show as '?'.
std::array<uint8_t, kGlyphHeight> Glyph(char c);

// An 8-bit coverage atlas of all glyphs side by side in one row of cells
// (width = kCellWidth * glyph count, height = kCellHeight), top row first.
struct FontAtlas {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> coverage;  // 255 where a glyph pixel is set
};
FontAtlas MakeFontAtlas();

}  // namespace simpartner
