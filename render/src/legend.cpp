#include "legend.hpp"

#include <algorithm>
#include <charconv>
#include <optional>
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

namespace {

// Where everything of the legend goes in a width x height viewport.
struct Layout {
  int s = 1;  // integer font scale
  int margin = 0, gap = 0, bar_w = 0, bar_h = 0;
  int bar_x0 = 0, bar_x1 = 0, bar_y0 = 0, bar_y1 = 0;
  std::string max_text, min_text, label;  // label wrapped to the column
  int label_x = 0;
  int column_left = 0;  // leftmost legend pixel, less a margin: the scene is drawn left of it
};

std::optional<Layout> layout_at_scale(const ColorMap& map, int width, int height, int s) {
  Layout l;
  l.s = s;
  l.margin = 12 * s;
  l.gap = 4 * s;  // between bar and numbers
  l.bar_w = 8 * s;
  l.bar_h = height * 2 / 5;
  l.max_text = format_number(map.max);
  l.min_text = format_number(map.min);
  const int numbers_w = std::max(text_width(l.max_text, s), text_width(l.min_text, s));
  l.bar_x1 = width - l.margin - numbers_w - l.gap;
  l.bar_x0 = l.bar_x1 - l.bar_w;
  l.bar_y0 = (height - l.bar_h) / 2;
  l.bar_y1 = l.bar_y0 + l.bar_h;
  l.column_left = l.bar_x0 - s;
  if (!map.label.empty()) {
    // Above the max value, wrapped at spaces to the column of bar and numbers (a single word
    // wider than that keeps its line and widens the column); lines flush left, the block
    // right-aligned with the numbers.
    l.label = wrap_words(map.label, numbers_w + l.gap + l.bar_w + s, s);
    l.label_x = std::max(width - l.margin - text_width(l.label, s), 0);
    l.column_left = std::min(l.column_left, l.label_x);
  }
  l.column_left -= l.margin;
  if (l.bar_h < 16 || l.column_left < width / 2) return std::nullopt;
  return l;
}

// Layout in font units times an integer scale, height / 360 rounded: 1 below 540 px, 2 at 600
// and 720 px, 3 at 1080 px, at most 4; smaller where the column would take more than half the
// width (a tall, narrow view: each half of a side-by-side window), so that a colour map is
// never shown without its legend unless even the smallest font does not fit.
std::optional<Layout> layout(const ColorMap& map, int width, int height) {
  for (int s = std::clamp((height + 180) / 360, 1, 4); s >= 1; --s)
    if (auto l = layout_at_scale(map, width, height, s)) return l;
  return std::nullopt;
}

}  // namespace

int legend_width(const ColorMap& map, int width, int height) {
  if (!map.show_legend) return 0;
  const auto l = layout(map, width, height);
  return l ? width - l->column_left : 0;
}

std::vector<OverlayVertex> legend_triangles(const ColorMap& map, int width, int height,
                                            const Color& background) {
  const auto layout_or_none = layout(map, width, height);
  if (!layout_or_none) return {};
  const Layout& l = *layout_or_none;
  const int s = l.s, gap = l.gap;
  const int bar_x0 = l.bar_x0, bar_x1 = l.bar_x1, bar_y0 = l.bar_y0, bar_y1 = l.bar_y1;
  const std::string& max_text = l.max_text;
  const std::string& min_text = l.min_text;

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
  if (!l.label.empty()) {
    const int lines = 1 + static_cast<int>(std::count(l.label.begin(), l.label.end(), '\n'));
    const int y = bar_y0 - half_cap - gap - kTextDescentUnits * s - (lines - 1) * kTextLineUnits * s;
    list.text(l.label, l.label_x, std::max(y, 0), s, ink);
  }
  return out;
}

}  // namespace sutura::render
