#pragma once
// Pages of line art, labels and pictures at true scale, written as SVG or PDF: printed at
// 100 %, one millimetre on the page is one millimetre of the drawing (a cutting template, the
// pages of a plan report).
//
// Both writers are our own, not Cairo's: the pages hold only straight strokes, ASCII labels in
// a standard font (SVG: sans-serif; PDF: the base-14 Helvetica, which every reader has, so
// nothing is embedded) and RGB pictures. Written by hand the bytes are deterministic (no
// creation date), the PDF's content streams are uncompressed (a test reads their coordinates;
// pictures are deflated by stb), and no library is opened at start-up. docs/patch-design.md
// gives the choice in full.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "sutura/render/image.hpp"

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

/// A picture scaled into a rectangle of the page (its alpha is ignored: drawn opaque).
struct PageImage {
  PagePoint at;  ///< the top-left corner
  double width_mm = 0.0, height_mm = 0.0;  ///< each > 0
  Image image;  ///< at least 1 x 1
};

/// Drawn in this order: images, strokes, labels.
struct VectorPage {
  double width_mm = 210.0, height_mm = 297.0;  ///< A4 portrait by default; each > 0
  std::string title;  ///< document title (PDF Info, SVG <title>)
  std::vector<PageImage> images;
  std::vector<PageStroke> strokes;
  std::vector<PageLabel> labels;
};

/// The advance width (mm) of `text` set in Helvetica at `size_mm` (Adobe's metrics; the bytes
/// a label writes as '?' count as '?'): what a layout needs to wrap or centre a label.
double text_width_mm(const std::string& text, double size_mm);

/// SVG 1.1 text: width/height in mm and a viewBox in mm, so one user unit is one millimetre;
/// pictures as PNG data URIs. Throws std::invalid_argument for a non-positive or non-finite
/// page size, a stroke of fewer than two points, a non-finite coordinate or an empty or
/// non-positive picture. Cost O(points + characters + pixels).
std::string to_svg(const VectorPage& page);

/// PDF 1.4 bytes of one page or more (`title`: the document's; each page's own title is not
/// used). Each page's MediaBox is its size in points (72 per inch); it is drawn in mm by a
/// `cm` scale of 72 / 25.4 with y flipped, in one uncompressed content stream; each picture is
/// an RGB image XObject deflated by stb; a valid cross-reference table. Same errors and cost
/// as to_svg, and std::invalid_argument for no page.
std::string to_pdf(std::span<const VectorPage> pages, const std::string& title);
/// The one page, under its own title.
std::string to_pdf(const VectorPage& page);

}  // namespace sutura::render
