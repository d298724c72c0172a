#include "text.hpp"

#include <cmath>
#include <string>

// stb_easy_font is header-only with static functions, some of which are unused here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace sutura::render {
namespace {

// stb_easy_font indexes its glyph table with (char - 32) and has no bounds check.
std::string printable(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c != '\n' && (c < 32 || c > 126)) c = '?';
  }
  return out;
}

// One stb_easy_font vertex: x, y, z as float, then 4 colour bytes; 4 vertices per quad.
struct FontVertex {
  float x, y, z;
  unsigned char rgba[4];
};
static_assert(sizeof(FontVertex) == 16);

}  // namespace

std::vector<TextRect> text_rects(std::string_view text, int x, int y, int scale) {
  std::string chars = printable(text);
  // No glyph of the font needs more than 11 quads; 20 leaves room.
  std::vector<FontVertex> vertices(chars.size() * 4 * 20 + 4);
  const int quads = stb_easy_font_print(0.0f, 0.0f, chars.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size() * sizeof(FontVertex)));
  std::vector<TextRect> rects;
  rects.reserve(static_cast<std::size_t>(quads));
  for (int q = 0; q < quads; ++q) {
    // Vertices 0 and 2 of each quad are opposite corners; coordinates are whole font units.
    const FontVertex& a = vertices[static_cast<std::size_t>(4 * q)];
    const FontVertex& b = vertices[static_cast<std::size_t>(4 * q + 2)];
    rects.push_back({x + scale * static_cast<int>(std::lround(a.x)),
                     y + scale * static_cast<int>(std::lround(a.y)),
                     x + scale * static_cast<int>(std::lround(b.x)),
                     y + scale * static_cast<int>(std::lround(b.y))});
  }
  return rects;
}

int text_width(std::string_view text, int scale) {
  std::string chars = printable(text);
  return scale * stb_easy_font_width(chars.data());
}

}  // namespace sutura::render
