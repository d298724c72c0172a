#pragma once
// A page of line art and labels at true scale, written as SVG or PDF: printed at 100 %, one
// millimetre on the page is one millimetre of the drawing (a cutting template).
//
// Both writers are our own, not Cairo's: the page holds only straight strokes and a few ASCII
// labels in a standard font (SVG: sans-serif; PDF: the base-14 Helvetica, which every reader
// has, so nothing is embedded). Written by hand the bytes are deterministic (no creation date),
// the PDF's content stream is uncompressed (a test reads its coordinates), and no library is
// opened at start-up. docs/patch-design.md gives the choice in full.
#include <array>
#include <string>
#include <vector>

namespace sutura::render {

/// Page coordinates in mm, origin at the top-left corner, y downwards.
using PagePoint = std::array<double, 2>;

struct PageStroke {
  std::vector<PagePoint> points;  ///< at least 2
  bool closed = false;
  double width_mm = 0.25;
  /// Dash pattern in mm (on, off, ...); empty = solid.
  std::vector<double> dash_mm;
  double grey = 0.0;  ///< 0 black ... 1 white
};

struct PageLabel {
  PagePoint at;  ///< the baseline's start, or its middle when `centred`
  std::string text;  ///< printable ASCII; other bytes are written as '?'
  double size_mm = 3.0;  ///< the font size (em), mm
  bool centred = false;
};

struct VectorPage {
  double width_mm = 210.0, height_mm = 297.0;  ///< A4 portrait by default; each > 0
  std::string title;  ///< document title (PDF Info, SVG <title>)
  std::vector<PageStroke> strokes;
  std::vector<PageLabel> labels;
};

/// SVG 1.1 text: width/height in mm and a viewBox in mm, so one user unit is one millimetre.
/// Throws std::invalid_argument for a non-positive or non-finite page size, a stroke of fewer
/// than two points, or a non-finite coordinate. Cost O(points + characters).
std::string to_svg(const VectorPage& page);

/// PDF 1.4 bytes: one page whose MediaBox is the page size in points (72 per inch), drawn in
/// mm by a `cm` scale of 72 / 25.4 with y flipped, in one uncompressed content stream; a valid
/// cross-reference table. Same errors and cost as to_svg.
std::string to_pdf(const VectorPage& page);

}  // namespace sutura::render
