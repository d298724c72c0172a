// Vector pages (SVG, PDF) at true scale.
#include "sutura/render/vector_page.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

namespace sutura::render {
namespace {

VectorPage scale_bar_page() {
  VectorPage p;
  p.title = "scale (check) & <bar>";
  PageStroke bar;
  bar.points = {{20.0, 30.0}, {30.0, 30.0}};
  bar.width_mm = 0.3;
  p.strokes.push_back(bar);
  PageStroke dashed;
  dashed.points = {{50, 50}, {60, 50}, {60, 70}};
  dashed.closed = true;
  dashed.dash_mm = {1.0, 0.5};
  dashed.grey = 0.5;
  p.strokes.push_back(dashed);
  p.labels.push_back({{25.0, 27.0}, "10 mm", 3.0, true});
  p.labels.push_back({{20.0, 40.0}, "a (b) \\ c \xC3\xA9", 2.5, false});
  return p;
}

// One user unit of the SVG is a millimetre: the page is given in mm and its viewBox in the
// same numbers, and the bar's end points are 10 units apart.
TEST(VectorPage, SvgIsInMillimetres) {
  const std::string svg = to_svg(scale_bar_page());
  EXPECT_NE(svg.find("width=\"210mm\" height=\"297mm\" viewBox=\"0 0 210 297\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("<polyline points=\"20,30 30,30\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("<polygon points=\"50,50 60,50 60,70\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("stroke-dasharray=\"1 0.5\""), std::string::npos);
  EXPECT_NE(svg.find("<title>scale (check) &amp; &lt;bar&gt;</title>"), std::string::npos);
  EXPECT_NE(svg.find("text-anchor=\"middle\">10 mm</text>"), std::string::npos);
  EXPECT_NE(svg.find(">a (b) \\ c ?\?</text>"), std::string::npos) << "non-ASCII bytes become '?'";
  EXPECT_EQ(svg, to_svg(scale_bar_page())) << "deterministic";
}

// The PDF's page is A4 in points; its content is drawn in mm through one scale of 72/25.4, so
// the bar's 10 units are 28.35 pt; the cross-reference table points at each object.
TEST(VectorPage, PdfIsAtTrueScaleAndWellFormed) {
  const std::string pdf = to_pdf(scale_bar_page());
  ASSERT_EQ(pdf.rfind("%PDF-1.4\n", 0), 0u);
  EXPECT_NE(pdf.find("/MediaBox [0 0 595.2756 841.8898]"), std::string::npos);
  EXPECT_NE(pdf.find("2.834646 0 0 -2.834646 0 841.889764 cm"), std::string::npos);
  EXPECT_NE(pdf.find("20 30 m\n30 30 l\nS\n"), std::string::npos) << "the bar, in mm";
  EXPECT_NE(pdf.find("50 50 m\n60 50 l\n60 70 l\ns\n"), std::string::npos);
  EXPECT_NE(pdf.find("[1 0.5] 0 d"), std::string::npos);
  EXPECT_NE(pdf.find("(a \\(b\\) \\\\ c ?\?) Tj"), std::string::npos);
  // "10 mm" centred on x = 25 at 3 mm: Helvetica widths 556+556+278+833+833 = 3056/1000 em.
  EXPECT_NE(pdf.find(" 20.416 27 Tm (10 mm) Tj"), std::string::npos) << pdf;

  // Cross-references: each of the six objects starts where the table says.
  const std::size_t startxref = pdf.rfind("startxref\n");
  ASSERT_NE(startxref, std::string::npos);
  const std::size_t xref = std::stoul(pdf.substr(startxref + 10));
  ASSERT_EQ(pdf.compare(xref, 5, "xref\n"), 0);
  std::istringstream table(pdf.substr(xref + 5));
  int first = -1, count = 0;
  table >> first >> count;
  ASSERT_EQ(first, 0);
  ASSERT_EQ(count, 7);
  std::string offset, generation, kind;
  table >> offset >> generation >> kind;
  EXPECT_EQ(kind, "f");
  for (int i = 1; i < count; ++i) {
    table >> offset >> generation >> kind;
    ASSERT_EQ(kind, "n");
    const std::string head = std::to_string(i) + " 0 obj\n";
    EXPECT_EQ(pdf.compare(std::stoul(offset), head.size(), head), 0) << "object " << i;
  }
  // The content stream's length is its byte count.
  const std::size_t at = pdf.find("/Length ");
  const std::size_t length = std::stoul(pdf.substr(at + 8));
  const std::size_t begin = pdf.find("stream\n", at) + 7;
  EXPECT_EQ(pdf.compare(begin + length, 9, "endstream"), 0);
  EXPECT_EQ(pdf, to_pdf(scale_bar_page())) << "deterministic";
}

TEST(VectorPage, RefusesBadPages) {
  VectorPage p = scale_bar_page();
  p.width_mm = 0;
  EXPECT_THROW((void)to_svg(p), std::invalid_argument);
  p = scale_bar_page();
  p.strokes[0].points.resize(1);
  EXPECT_THROW((void)to_pdf(p), std::invalid_argument);
  p = scale_bar_page();
  p.strokes[0].points[1][0] = std::nan("");
  EXPECT_THROW((void)to_pdf(p), std::invalid_argument);
  p = scale_bar_page();
  p.strokes[1].dash_mm = {1.0, 0.0};
  EXPECT_THROW((void)to_svg(p), std::invalid_argument);
}

}  // namespace
}  // namespace sutura::render
