// Vector pages (SVG, PDF) at true scale.
#include "sutura/render/vector_page.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "pdf_structure.hpp"
#include "sutura/render/image.hpp"

// Debian's libstb exports stb_image's inflate; the header declares it only inside its
// implementation section.
extern "C" char* stbi_zlib_decode_malloc(const char* buffer, int len, int* outlen);

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

  // Cross-references: each of the six objects starts where the table says; the content
  // stream's length is its byte count.
  EXPECT_TRUE(sutura::testing::pdf_structure_holds(pdf, 6));
  EXPECT_EQ(pdf, to_pdf(scale_bar_page())) << "deterministic";
}

Image two_by_two() {
  Image im(2, 2);
  im.set_pixel(0, 0, {255, 0, 0, 255});
  im.set_pixel(1, 0, {0, 255, 0, 255});
  im.set_pixel(0, 1, {0, 0, 255, 255});
  im.set_pixel(1, 1, {10, 20, 30, 128});  // alpha is ignored
  return im;
}

// Base64 digits back to bytes (test-only inverse of png_data_uri's encoding).
std::vector<std::uint8_t> from_base64(const std::string& text) {
  const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<std::uint8_t> out;
  std::uint32_t v = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    const std::size_t d = digits.find(c);
    if (d == std::string::npos) throw std::runtime_error("not base64");
    v = (v << 6) | static_cast<std::uint32_t>(d);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((v >> bits) & 0xFF));
    }
  }
  return out;
}

TEST(VectorPage, DataUriHoldsThePng) {
  const Image im = two_by_two();
  const std::string uri = png_data_uri(im);
  ASSERT_EQ(uri.rfind("data:image/png;base64,", 0), 0u);
  const std::string digits = uri.substr(22);
  EXPECT_EQ(digits.size() % 4, 0u) << "padded";
  EXPECT_EQ(from_base64(digits), encode_png(im));
}

// Several pages, pictures on the second: the page tree counts them, each page has its own
// content, and a picture is drawn into its rectangle (first row at the top) from deflated RGB
// bytes that inflate back to the image's.
TEST(VectorPage, PdfPagesWithPictures) {
  VectorPage a = scale_bar_page(), b;
  b.width_mm = 100.0;
  b.height_mm = 50.0;
  b.images.push_back({{20.0, 30.0}, 10.0, 5.0, two_by_two()});
  const std::vector<VectorPage> pages = {a, b};
  const std::string pdf = to_pdf(pages, "two pages");
  EXPECT_NE(pdf.find("<< /Type /Pages /Kids [5 0 R 7 0 R] /Count 2 >>"), std::string::npos) << pdf.substr(0, 400);
  EXPECT_NE(pdf.find("/Title (two pages)"), std::string::npos);
  EXPECT_NE(pdf.find("/XObject << /Im1 9 0 R >>"), std::string::npos);
  EXPECT_NE(pdf.find("q 10 0 0 -5 20 35 cm /Im1 Do Q\n"), std::string::npos);
  const std::size_t head = pdf.find("/Subtype /Image /Width 2 /Height 2 /ColorSpace /DeviceRGB");
  ASSERT_NE(head, std::string::npos);
  const std::size_t at = pdf.find("/Length ", head);
  const std::size_t length = std::stoul(pdf.substr(at + 8));
  const std::size_t begin = pdf.find("stream\n", at) + 7;
  int n = 0;
  char* raw = stbi_zlib_decode_malloc(pdf.data() + begin, static_cast<int>(length), &n);
  ASSERT_NE(raw, nullptr);
  const std::string rgb(raw, static_cast<std::size_t>(n));
  std::free(raw);
  EXPECT_TRUE(sutura::testing::pdf_structure_holds(pdf, 9)) << "4, 2 a page and 1 picture";
  EXPECT_EQ(rgb, std::string("\xFF\x00\x00\x00\xFF\x00\x00\x00\xFF\x0A\x14\x1E", 12));
  EXPECT_EQ(pdf, to_pdf(pages, "two pages")) << "deterministic";
  EXPECT_THROW((void)to_pdf(std::vector<VectorPage>{}, "none"), std::invalid_argument);
}

TEST(VectorPage, SvgPictureIsADataUri) {
  VectorPage p;
  p.images.push_back({{1.0, 2.0}, 30.0, 15.0, two_by_two()});
  const std::string svg = to_svg(p);
  EXPECT_NE(svg.find("<image x=\"1\" y=\"2\" width=\"30\" height=\"15\" preserveAspectRatio=\"none\" href=\"" +
                     png_data_uri(two_by_two()) + "\"/>"),
            std::string::npos);
}

TEST(VectorPage, TextWidthIsHelvetica) {
  // "10 mm": 556 + 556 + 278 + 833 + 833 = 3056/1000 em.
  EXPECT_DOUBLE_EQ(text_width_mm("10 mm", 3.0), 3.0 * 3.056);
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
  p = scale_bar_page();
  p.images.push_back({{0.0, 0.0}, 0.0, 5.0, two_by_two()});
  EXPECT_THROW((void)to_pdf(p), std::invalid_argument);
  p.images.back().width_mm = 5.0;
  p.images.back().image = Image();
  EXPECT_THROW((void)to_svg(p), std::invalid_argument);
}

}  // namespace
}  // namespace sutura::render
