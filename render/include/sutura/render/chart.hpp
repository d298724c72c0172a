#pragma once
// A line chart drawn on the CPU into an image (then PNG): the plots of reports, such as
// design_patch's lumen and bulge against the patch's width. No GL, deterministic pixels.
//
// Layout: the plot area inside fixed margins, a left y axis and, when a series asks for it, a
// right one, each with "nice" ticks (1, 2 or 5 times a power of ten); horizontal bands (a
// target range) under the series, vertical markers (a chosen value) over them, a legend in
// the top-left corner of the plot area. Text uses the captions' bitmap font (ASCII).
#include <array>
#include <string>
#include <vector>

#include "sutura/render/image.hpp"

namespace sutura::render {

struct ChartSeries {
  std::string label;
  std::vector<std::array<double, 2>> points;  ///< (x, y), joined in the order given
  Rgba color{31, 119, 180, 255};
  bool right_axis = false;  ///< scaled on the right-hand axis
};

/// A horizontal band [low, high] on one axis (e.g. a target with its tolerance).
struct ChartBand {
  double low = 0.0, high = 0.0;
  bool right_axis = false;
  Rgba color{200, 230, 200, 255};
};

/// A vertical line at x, labelled at its top.
struct ChartMarker {
  double x = 0.0;
  std::string label;
};

struct Chart {
  int width = 960, height = 600;  ///< pixels, each in [200, 4096]
  std::string title, x_label, y_label, y2_label;
  std::vector<ChartSeries> series;
  std::vector<ChartBand> bands;
  std::vector<ChartMarker> markers;
};

/// The chart as an opaque white image of chart.width x chart.height. Axis ranges cover every
/// point, band and marker with 5 % to spare. Throws std::invalid_argument for a size out of
/// range, no series, a series without points or a non-finite value. Cost O(pixels + points).
Image draw_chart(const Chart& chart);

}  // namespace sutura::render
