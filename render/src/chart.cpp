#include "sutura/render/chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "text.hpp"

namespace sutura::render {

namespace {

constexpr int kLeft = 100, kRight = 100, kTop = 84, kBottom = 76;
constexpr int kTextScale = 2;
constexpr Rgba kInk{40, 40, 40, 255};
constexpr Rgba kGrid{225, 225, 225, 255};

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) throw std::invalid_argument("chart: a value is not finite");
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  [[nodiscard]] bool empty() const { return !(lo <= hi); }
  // 5 % to spare each side, and at least 1e-6 of the values' size (a single value, or values
  // a few ulps apart, get a range the ticks can step through).
  void pad() {
    if (!std::isfinite(hi - lo)) throw std::invalid_argument("chart: the values span more than a double holds");
    const double floor = 1e-6 * std::max({1.0, std::abs(lo), std::abs(hi)});
    const double margin = std::max(0.05 * (hi - lo), floor);
    lo -= margin;
    hi += margin;
  }
};

// Tick spacing: 1, 2 or 5 x 10^k giving about `count` intervals.
double tick_step(const Range& r, int count) {
  const double raw = (r.hi - r.lo) / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

std::string tick_text(double v, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < 1e-12 * step ? 0.0 : v);
  return buf;
}

void fill(Image& im, int x0, int y0, int x1, int y1, Rgba c) {
  x0 = std::max(x0, 0), y0 = std::max(y0, 0);
  x1 = std::min(x1, im.width), y1 = std::min(y1, im.height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) im.set_pixel(x, y, c);
}

void text(Image& im, const std::string& s, int x, int y, Rgba c) {
  for (const TextRect& r : text_rects(s, x, y, kTextScale)) fill(im, r.x0, r.y0, r.x1, r.y1, c);
}

int text_height() { return kTextScale * kTextCapUnits; }

// A line `width` pixels thick: squares stamped along it, one per pixel of its length.
void line(Image& im, double x0, double y0, double x1, double y1, int width, Rgba c) {
  const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))));
  const int h = width / 2;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
    const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    fill(im, x - h, y - h, x - h + width, y - h + width, c);
  }
}

}  // namespace

Image draw_chart(const Chart& chart) {
  if (chart.width < 200 || chart.width > 4096 || chart.height < 200 || chart.height > 4096)
    throw std::invalid_argument("chart: the size must be 200 ... 4096 pixels each way");
  if (chart.series.empty()) throw std::invalid_argument("chart: no series");
  Range xr, yr[2];
  for (const ChartSeries& s : chart.series) {
    if (s.points.empty()) throw std::invalid_argument("chart: the series '" + s.label + "' has no points");
    for (const auto& p : s.points) {
      xr.add(p[0]);
      yr[s.right_axis].add(p[1]);
    }
  }
  for (const ChartBand& b : chart.bands) {
    yr[b.right_axis].add(b.low);
    yr[b.right_axis].add(b.high);
  }
  for (const ChartMarker& m : chart.markers) xr.add(m.x);
  xr.pad();
  for (Range& r : yr)
    if (!r.empty()) r.pad();

  Image im(chart.width, chart.height);
  const int px0 = kLeft, px1 = chart.width - kRight, py0 = kTop, py1 = chart.height - kBottom;
  auto X = [&](double x) { return px0 + (x - xr.lo) / (xr.hi - xr.lo) * (px1 - px0); };
  auto Y = [&](double y, bool right) {
    const Range& r = yr[right];
    return py1 - (y - r.lo) / (r.hi - r.lo) * (py1 - py0);
  };

  // Bands, then the grid and ticks, then series, markers, frame and text.
  for (const ChartBand& b : chart.bands)
    fill(im, px0, static_cast<int>(std::lround(Y(b.high, b.right_axis))), px1,
         static_cast<int>(std::lround(Y(b.low, b.right_axis))) + 1, b.color);
  // Tick k is at k * step for k over the range (at most about 12 of them by tick_step).
  auto ticks = [](const Range& r, double step) {
    std::vector<double> out;
    for (double k = std::ceil(r.lo / step); k <= std::floor(r.hi / step) && out.size() < 64; k += 1.0)
      out.push_back(k * step);
    return out;
  };
  const double xs = tick_step(xr, 6);
  for (double t : ticks(xr, xs)) {
    const int x = static_cast<int>(std::lround(X(t)));
    fill(im, x, py0, x + 1, py1, kGrid);
    const std::string s = tick_text(t, xs);
    text(im, s, x - text_width(s, kTextScale) / 2, py1 + 10, kInk);
  }
  for (int side = 0; side < 2; ++side) {
    if (yr[side].empty()) continue;
    const double ys = tick_step(yr[side], 5);
    for (double t : ticks(yr[side], ys)) {
      const int y = static_cast<int>(std::lround(Y(t, side == 1)));
      if (side == 0) fill(im, px0, y, px1, y + 1, kGrid);
      const std::string s = tick_text(t, ys);
      const int x = side == 0 ? px0 - 10 - text_width(s, kTextScale) : px1 + 10;
      text(im, s, x, y - text_height() / 2, kInk);
    }
  }
  for (const ChartSeries& s : chart.series) {
    for (std::size_t i = 0; i + 1 < s.points.size(); ++i)
      line(im, X(s.points[i][0]), Y(s.points[i][1], s.right_axis), X(s.points[i + 1][0]),
           Y(s.points[i + 1][1], s.right_axis), 3, s.color);
    for (const auto& p : s.points) {
      const int x = static_cast<int>(std::lround(X(p[0]))), y = static_cast<int>(std::lround(Y(p[1], s.right_axis)));
      fill(im, x - 5, y - 5, x + 6, y + 6, s.color);
    }
  }
  for (const ChartMarker& m : chart.markers) {
    const double x = X(m.x);
    for (int y = py0; y < py1; y += 12) line(im, x, y, x, std::min(y + 6, py1), 2, kInk);
    text(im, m.label, static_cast<int>(std::lround(x)) - text_width(m.label, kTextScale) / 2, py0 - 6 - text_height(), kInk);
  }
  line(im, px0, py0, px1, py0, 1, kInk);
  line(im, px0, py1, px1, py1, 1, kInk);
  line(im, px0, py0, px0, py1, 1, kInk);
  line(im, px1, py0, px1, py1, 1, kInk);

  text(im, chart.title, (chart.width - text_width(chart.title, kTextScale)) / 2, 8, kInk);
  text(im, chart.x_label, (px0 + px1 - text_width(chart.x_label, kTextScale)) / 2, py1 + 40, kInk);
  text(im, chart.y_label, 8, 36, kInk);
  if (!chart.y2_label.empty())
    text(im, chart.y2_label, chart.width - 8 - text_width(chart.y2_label, kTextScale), 36, kInk);
  int ly = py0 + 10;
  for (const ChartSeries& s : chart.series) {
    fill(im, px0 + 10, ly + 2, px0 + 34, ly + 8, s.color);
    std::string label = s.label;
    if (s.right_axis && !yr[0].empty()) label += " (right axis)";
    text(im, label, px0 + 42, ly, kInk);
    ly += 26;
  }
  return im;
}

}  // namespace sutura::render
