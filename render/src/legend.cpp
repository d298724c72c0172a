#include "legend.hpp"

#include <algorithm>
#include <charconv>
#include <string>

#include "text.hpp"

namespace sutura::render {
namespace {

std::string format_number(float value) {
  char buffer[32];
  // + 0.0f turns -0 into 0; to_chars ignores the locale.
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value + 0.0f, std::chars_format::general, 4);
  return {buffer, result.ptr};
}

class TriangleList {
 public:
  explicit TriangleList(std::vector<OverlayVertex>& out) : out_(out) {}

  /// Axis-aligned rectangle in one colour.
  void rect(float x0, float y0, float x1, float y1, const Color& c) {
    quad(x0, y0, x1, y1, -1.0f, -1.0f, c);
  }
  /// Rectangle sampling the colour map, from `top` at y0 to `bottom` at y1.
  void gradient(float x0, float y0, float x1, float y1, float top, float bottom) {
    quad(x0, y0, x1, y1, top, bottom, {0.0f, 0.0f, 0.0f});
  }
  void text(const std::string& s, int x, int y, int scale, const Color& c) {
    for (const TextRect& r : text_rects(s, x, y, scale)) {
      rect(static_cast<float>(r.x0), static_cast<float>(r.y0), static_cast<float>(r.x1),
           static_cast<float>(r.y1), c);
    }
  }

 private:
  void quad(float x0, float y0, float x1, float y1, float s_top, float s_bottom, const Color& c) {
    const OverlayVertex a{x0, y0, s_top, c[0], c[1], c[2]};
    const OverlayVertex b{x1, y0, s_top, c[0], c[1], c[2]};
    const OverlayVertex d{x0, y1, s_bottom, c[0], c[1], c[2]};
    const OverlayVertex e{x1, y1, s_bottom, c[0], c[1], c[2]};
    for (const OverlayVertex* v : {&a, &b, &d, &b, &e, &d}) out_.push_back(*v);
  }
  std::vector<OverlayVertex>& out_;
};

// `text` with spaces turned into line breaks wherever a line would exceed `max_width` pixels.
std::string wrap_words(const std::string& text, int max_width, int scale) {
  std::string out, line;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(' ', start), text.size());
    const std::string word = text.substr(start, end - start);
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(longer, scale) > max_width) {
      out += line + "\n";
      line = word;
    } else {
      line = longer;
    }
    start = end + 1;
  }
  return out + line;
}

}  // namespace

std::vector<OverlayVertex> legend_triangles(const ColorMap& map, int width, int height,
                                            const Color& background) {
  // Layout in font units times an integer scale, height / 360 rounded: 1 below 540 px,
  // 2 at 600 and 720 px, 3 at 1080 px, at most 4.
  const int s = std::clamp((height + 180) / 360, 1, 4);
  const int margin = 12 * s;
  const int gap = 4 * s;  // between bar and numbers
  const int bar_w = 8 * s;
  const int bar_h = height * 2 / 5;
  const std::string max_text = format_number(map.max);
  const std::string min_text = format_number(map.min);
  const int numbers_w = std::max(text_width(max_text, s), text_width(min_text, s));
  const int bar_x1 = width - margin - numbers_w - gap;
  const int bar_x0 = bar_x1 - bar_w;
  if (bar_h < 16 || bar_x0 - s < width / 2) return {};
  const int bar_y0 = (height - bar_h) / 2;
  const int bar_y1 = bar_y0 + bar_h;

  // Relative luminance of the linear background colour.
  const float luminance =
      0.2126f * background[0] + 0.7152f * background[1] + 0.0722f * background[2];
  const Color ink = luminance > 0.18f ? Color{0.01f, 0.01f, 0.01f} : Color{0.9f, 0.9f, 0.9f};

  std::vector<OverlayVertex> out;
  TriangleList list(out);
  list.rect(static_cast<float>(bar_x0 - s), static_cast<float>(bar_y0 - s),
            static_cast<float>(bar_x1 + s), static_cast<float>(bar_y1 + s), ink);
  list.gradient(static_cast<float>(bar_x0), static_cast<float>(bar_y0), static_cast<float>(bar_x1),
                static_cast<float>(bar_y1), 1.0f, 0.0f);
  // Numbers centred vertically on the bar's ends.
  const int half_cap = (kTextCapUnits * s + 1) / 2;
  list.text(max_text, bar_x1 + gap, bar_y0 - half_cap, s, ink);
  list.text(min_text, bar_x1 + gap, bar_y1 - half_cap, s, ink);
  if (!map.label.empty()) {
    // Above the max value, wrapped at spaces to the right third of the picture so that a
    // long label ("max principal membrane strain [-] (top 0.5 % clipped)") does not run
    // across the object in the middle; lines flush left, the block right-aligned with the
    // numbers. A single word wider than that keeps its line.
    const std::string text = wrap_words(map.label, std::max(width / 3, numbers_w + gap + bar_w), s);
    const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    const int x = std::max(width - margin - text_width(text, s), 0);
    const int y = bar_y0 - half_cap - gap - kTextDescentUnits * s - (lines - 1) * kTextLineUnits * s;
    list.text(text, x, std::max(y, 0), s, ink);
  }
  return out;
}

}  // namespace sutura::render
