#include "sutura/render/vector_page.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <system_error>
#include <stdexcept>

// Debian's libstb exports stb_image_write's deflate (zlib format) but its header declares it
// only inside the implementation section. The result is malloc'ed.
extern "C" unsigned char* stbi_zlib_compress(unsigned char* data, int data_len, int* out_len, int quality);

namespace sutura::render {

namespace {

// Fixed-point text of a coordinate, locale-independent, trailing zeros dropped.
std::string num(double v, int decimals = 4) {
  if (!std::isfinite(v)) throw std::invalid_argument("vector page: a coordinate is not finite");
  if (std::abs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0.0;  // no "-0"
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) throw std::invalid_argument("vector page: a coordinate is too large");
  std::string s(buf, r.ptr);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

std::string printable(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

void check(const VectorPage& page) {
  if (!(page.width_mm > 0) || !(page.height_mm > 0) || !std::isfinite(page.width_mm) ||
      !std::isfinite(page.height_mm))
    throw std::invalid_argument("vector page: the page size must be positive and finite");
  for (const PageStroke& s : page.strokes) {
    if (s.points.size() < 2) throw std::invalid_argument("vector page: a stroke has fewer than two points");
    if (!(s.width_mm > 0) || !std::isfinite(s.width_mm))
      throw std::invalid_argument("vector page: a stroke width must be positive and finite");
    for (double d : s.dash_mm)
      if (!(d > 0) || !std::isfinite(d))
        throw std::invalid_argument("vector page: a dash length must be positive and finite");
  }
  for (const PageImage& i : page.images) {
    if (!(i.width_mm > 0) || !(i.height_mm > 0) || !std::isfinite(i.width_mm) || !std::isfinite(i.height_mm))
      throw std::invalid_argument("vector page: a picture's size must be positive and finite");
    if (i.image.width < 1 || i.image.height < 1 ||
        i.image.rgba.size() != 4 * static_cast<std::size_t>(i.image.width) * i.image.height)
      throw std::invalid_argument("vector page: a picture is empty or inconsistent");
  }
}

// The picture's RGB bytes, deflated (zlib format, PDF's FlateDecode).
std::string deflated_rgb(const Image& image) {
  std::vector<unsigned char> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
  for (std::size_t p = 0, q = 0; q < rgb.size(); p += 4, q += 3)
    for (int k = 0; k < 3; ++k) rgb[q + k] = image.rgba[p + k];
  if (rgb.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
    throw std::invalid_argument("vector page: a picture is too large");
  int length = 0;
  const std::unique_ptr<unsigned char, decltype(&std::free)> z(
      stbi_zlib_compress(rgb.data(), static_cast<int>(rgb.size()), &length, 8), &std::free);
  if (!z || length <= 0) throw std::runtime_error("vector page: deflating a picture failed");
  return {reinterpret_cast<const char*>(z.get()), static_cast<std::size_t>(length)};
}

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : printable(text)) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string pdf_string(const std::string& text) {
  std::string out = "(";
  for (char c : printable(text)) {
    if (c == '(' || c == ')' || c == '\\') out += '\\';
    out += c;
  }
  return out + ")";
}

// Advance widths of Helvetica, ASCII 32..126, in 1/1000 em (Adobe's AFM).
constexpr int kHelvetica[95] = {
    278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278,  // ' '../
    556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556,  // 0..?
    1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778, // @..O
    667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556,  // P.._
    333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556,  // `..o
    556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584};      // p..~

double helvetica_width_em(const std::string& text) {
  double w = 0.0;
  for (char c : printable(text)) w += kHelvetica[c - 32];
  return w / 1000.0;
}

}  // namespace

double text_width_mm(const std::string& text, double size_mm) { return size_mm * helvetica_width_em(text); }

std::string to_svg(const VectorPage& page) {
  check(page);
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + num(page.width_mm) +
       "mm\" height=\"" + num(page.height_mm) + "mm\" viewBox=\"0 0 " + num(page.width_mm) + " " +
       num(page.height_mm) + "\">\n";
  s += "<title>" + xml_escaped(page.title) + "</title>\n";
  for (const PageImage& i : page.images) {
    s += "<image x=\"" + num(i.at[0]) + "\" y=\"" + num(i.at[1]) + "\" width=\"" + num(i.width_mm) +
         "\" height=\"" + num(i.height_mm) + "\" preserveAspectRatio=\"none\" href=\"";
    s += png_data_uri(i.image);
    s += "\"/>\n";
  }
  for (const PageStroke& st : page.strokes) {
    s += st.closed ? "<polygon points=\"" : "<polyline points=\"";
    for (std::size_t i = 0; i < st.points.size(); ++i) {
      if (i) s += ' ';
      s += num(st.points[i][0]);
      s += ',';
      s += num(st.points[i][1]);
    }
    const int g = static_cast<int>(std::lround(255.0 * std::clamp(st.grey, 0.0, 1.0)));
    s += "\" fill=\"none\" stroke=\"rgb(" + std::to_string(g) + "," + std::to_string(g) + "," +
         std::to_string(g) + ")\" stroke-width=\"" + num(st.width_mm) +
         "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
    if (!st.dash_mm.empty()) {
      s += " stroke-dasharray=\"";
      for (std::size_t i = 0; i < st.dash_mm.size(); ++i) {
        if (i) s += ' ';
        s += num(st.dash_mm[i]);
      }
      s += "\"";
    }
    s += "/>\n";
  }
  for (const PageLabel& l : page.labels) {
    s += "<text x=\"" + num(l.at[0]) + "\" y=\"" + num(l.at[1]) +
         "\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"" + num(l.size_mm) + "\"";
    if (l.centred) s += " text-anchor=\"middle\"";
    s += '>';
    s += xml_escaped(l.text);
    s += "</text>\n";
  }
  s += "</svg>\n";
  return s;
}

namespace {

// One page's content stream; its pictures are named /Im1, /Im2, ... in page.images order.
std::string page_content(const VectorPage& page) {
  constexpr double kPointsPerMm = 72.0 / 25.4;
  // Content: millimetres, y down, through one matrix.
  std::string c = num(kPointsPerMm, 6) + " 0 0 " + num(-kPointsPerMm, 6) + " 0 " +
                  num(page.height_mm * kPointsPerMm, 6) + " cm\n1 J 1 j\n";
  for (std::size_t k = 0; k < page.images.size(); ++k) {
    const PageImage& i = page.images[k];
    // The unit square of image space, its first row at the top, onto the rectangle (y down).
    c += "q " + num(i.width_mm) + " 0 0 " + num(-i.height_mm) + " " + num(i.at[0]) + " " +
         num(i.at[1] + i.height_mm) + " cm /Im" + std::to_string(k + 1) + " Do Q\n";
  }
  for (const PageStroke& st : page.strokes) {
    c += num(std::clamp(st.grey, 0.0, 1.0), 3) + " G " + num(st.width_mm) + " w [";
    for (std::size_t i = 0; i < st.dash_mm.size(); ++i) {
      if (i) c += ' ';
      c += num(st.dash_mm[i]);
    }
    c += "] 0 d\n";
    for (std::size_t i = 0; i < st.points.size(); ++i)
      c += num(st.points[i][0]) + " " + num(st.points[i][1]) + (i ? " l\n" : " m\n");
    c += st.closed ? "s\n" : "S\n";
  }
  for (const PageLabel& l : page.labels) {
    const double x = l.centred ? l.at[0] - 0.5 * l.size_mm * helvetica_width_em(l.text) : l.at[0];
    // The text matrix flips y back, so the glyphs stand upright on the flipped page.
    c += "0 g BT /F1 1 Tf " + num(l.size_mm) + " 0 0 " + num(-l.size_mm) + " " + num(x) + " " +
         num(l.at[1]) + " Tm " + pdf_string(l.text) + " Tj ET\n";
  }
  return c;
}

}  // namespace

std::string to_pdf(std::span<const VectorPage> pages, const std::string& title) {
  if (pages.empty()) throw std::invalid_argument("vector page: a PDF needs at least one page");
  for (const VectorPage& page : pages) check(page);
  constexpr double kPointsPerMm = 72.0 / 25.4;
  // Objects: 1 catalog, 2 page tree, 3 font, 4 info, then per page: the page, its content
  // stream and its pictures.
  std::vector<std::string> objects = {
      "", "",
      "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>",
      "<< /Title " + pdf_string(title) + " /Producer (Sutura) >>",
  };
  std::string kids;
  for (const VectorPage& page : pages) {
    const std::size_t page_object = objects.size() + 1;
    if (!kids.empty()) kids += ' ';
    kids += std::to_string(page_object) + " 0 R";
    std::string pictures;
    for (std::size_t k = 0; k < page.images.size(); ++k)
      pictures += "/Im" + std::to_string(k + 1) + " " + std::to_string(page_object + 2 + k) + " 0 R ";
    objects.push_back("<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + num(page.width_mm * kPointsPerMm, 4) + " " +
                      num(page.height_mm * kPointsPerMm, 4) + "] /Resources << /Font << /F1 3 0 R >>" +
                      (pictures.empty() ? std::string() : " /XObject << " + pictures + ">>") +
                      " >> /Contents " + std::to_string(page_object + 1) + " 0 R >>");
    const std::string c = page_content(page);
    objects.push_back("<< /Length " + std::to_string(c.size()) + " >>\nstream\n" + c + "endstream");
    for (const PageImage& i : page.images) {
      const std::string z = deflated_rgb(i.image);
      objects.push_back("<< /Type /XObject /Subtype /Image /Width " + std::to_string(i.image.width) +
                        " /Height " + std::to_string(i.image.height) +
                        " /ColorSpace /DeviceRGB /BitsPerComponent 8 /Filter /FlateDecode /Length " +
                        std::to_string(z.size()) + " >>\nstream\n" + z + "\nendstream");
    }
  }
  objects[0] = "<< /Type /Catalog /Pages 2 0 R >>";
  objects[1] = "<< /Type /Pages /Kids [" + kids + "] /Count " + std::to_string(pages.size()) + " >>";
  std::string pdf = "%PDF-1.4\n%\xE2\xE3\xCF\xD3\n";
  std::vector<std::size_t> offsets;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    offsets.push_back(pdf.size());
    pdf += std::to_string(i + 1);
    pdf += " 0 obj\n";
    pdf += objects[i];
    pdf += "\nendobj\n";
  }
  const std::size_t xref = pdf.size();
  pdf += "xref\n0 " + std::to_string(objects.size() + 1) + "\n0000000000 65535 f \n";
  for (std::size_t o : offsets) {
    char entry[32];
    std::snprintf(entry, sizeof entry, "%010zu 00000 n \n", o);
    pdf += entry;
  }
  pdf += "trailer\n<< /Size " + std::to_string(objects.size() + 1) +
         " /Root 1 0 R /Info 4 0 R >>\nstartxref\n" + std::to_string(xref) + "\n%%EOF\n";
  return pdf;
}

std::string to_pdf(const VectorPage& page) { return to_pdf(std::span<const VectorPage>(&page, 1), page.title); }

}  // namespace sutura::render
