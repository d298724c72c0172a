#pragma once
// Text as pixel rectangles, from stb_easy_font's segment bitmap font. Used on the GPU (legend)
// and on the CPU (image captions) alike, so both look the same.
//
// Font metrics, in font units (one unit = `scale` pixels): a line is 12 units high; capitals
// and digits occupy rows [0, 7) of it, descenders end at row 9. Advances (including the
// space after a glyph) are 3-7 units.
#include <string_view>
#include <vector>

namespace sutura::render {

/// Axis-aligned rectangle [x0, x1) x [y0, y1) in pixels, y pointing down.
struct TextRect {
  int x0, y0, x1, y1;
};

inline constexpr int kTextLineUnits = 12;
/// Font units from the top of a line to the bottom of capitals and digits.
inline constexpr int kTextCapUnits = 7;
/// Font units from the top of a line to the bottom of descenders (g, j, p, q, y).
inline constexpr int kTextDescentUnits = 9;

/// Rectangles covering `text` with the top-left of its first line at (x, y); `scale` >= 1
/// pixels per font unit. '\n' starts a new line; bytes outside printable ASCII draw as '?'.
/// Cost: O(characters), at most 11 rectangles per character.
std::vector<TextRect> text_rects(std::string_view text, int x, int y, int scale);

/// Width in pixels of the widest line of `text` at `scale`.
int text_width(std::string_view text, int scale);

}  // namespace sutura::render
