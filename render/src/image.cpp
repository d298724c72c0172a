#include "sutura/render/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "text.hpp"

namespace sutura::render {
namespace {

constexpr int kCaptionScale = 2;    // pixels per font unit
constexpr int kCaptionPadding = 6;  // pixels above and below the caption text

void check_size(int w, int h) {
  if (w < 0 || h < 0) {
    throw std::invalid_argument("image size " + std::to_string(w) + "x" + std::to_string(h) +
                                " is negative");
  }
}

std::size_t offset(const Image& image, int x, int y) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) {
    throw std::out_of_range("pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") outside a " + std::to_string(image.width) + "x" +
                            std::to_string(image.height) + " image");
  }
  return 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
              static_cast<std::size_t>(x));
}

void blit(const Image& src, Image& dst, int left, int top) {
  if (src.width == 0) return;
  const auto row_bytes = 4 * static_cast<std::size_t>(src.width);
  for (int y = 0; y < src.height; ++y) {
    std::memcpy(&dst.rgba[offset(dst, left, top + y)],
                &src.rgba[4 * static_cast<std::size_t>(y) * src.width], row_bytes);
  }
}

// Black text on light backgrounds, white on dark ones (Rec. 709 luma of the sRGB bytes).
Rgba text_color_for(Rgba background) {
  const double luma = 0.2126 * background[0] + 0.7152 * background[1] + 0.0722 * background[2];
  return luma > 128.0 ? Rgba{20, 20, 20, 255} : Rgba{235, 235, 235, 255};
}

// Draws `caption` centred over the column [left, left + width), clipped to that column.
void draw_caption(Image& canvas, const std::string& caption, int left, int width, Rgba color) {
  if (caption.empty() || width <= 0) return;
  const int x = left + (width - text_width(caption, kCaptionScale)) / 2;
  for (const TextRect& r : text_rects(caption, x, kCaptionPadding, kCaptionScale)) {
    for (int y = std::max(r.y0, 0); y < std::min(r.y1, canvas.height); ++y) {
      for (int px = std::max(r.x0, left); px < std::min(r.x1, left + width); ++px) {
        canvas.set_pixel(px, y, color);
      }
    }
  }
}

// stb's defaults (choose among the five PNG row filters per row, compression level 8) take
// about 0.3 s for a 1920x1080 render on the reference machine. The Sub filter at level 5
// takes about 0.1 s and gives files no larger for rendered images (flat background, smooth
// shading). These are process-wide stb settings, set once before the first encoding.
void configure_png_writer() {
  static std::once_flag once;
  std::call_once(once, [] {
    stbi_write_force_png_filter = 1;  // Sub
    stbi_write_png_compression_level = 5;
  });
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

Image::Image(int w, int h, Rgba fill) : width(w), height(h) {
  check_size(w, h);
  rgba.resize(4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (std::size_t i = 0; i < rgba.size(); i += 4) std::memcpy(&rgba[i], fill.data(), 4);
}

Rgba Image::pixel(int x, int y) const {
  const std::size_t i = offset(*this, x, y);
  return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

void Image::set_pixel(int x, int y, Rgba c) {
  std::memcpy(&rgba[offset(*this, x, y)], c.data(), 4);
}

std::vector<std::uint8_t> encode_png(const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != 4 * static_cast<std::size_t>(image.width) * image.height) {
    throw std::invalid_argument("encode_png: image " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " is empty or inconsistent");
  }
  configure_png_writer();
  // An opaque image (every render) is written as RGB: a quarter fewer bytes for stb's
  // single-threaded compressor, the largest cost of a big snapshot.
  bool opaque = true;
  for (std::size_t i = 3; i < image.rgba.size() && opaque; i += 4) opaque = image.rgba[i] == 255;
  std::vector<std::uint8_t> rgb;
  if (opaque) {
    rgb.resize(image.rgba.size() / 4 * 3);
    for (std::size_t p = 0, q = 0; p < image.rgba.size(); p += 4, q += 3)
      std::memcpy(&rgb[q], &image.rgba[p], 3);
  }
  const int channels = opaque ? 3 : 4;
  std::vector<std::uint8_t> png;
  if (stbi_write_png_to_func(append_bytes, &png, image.width, image.height, channels,
                             opaque ? rgb.data() : image.rgba.data(), channels * image.width) == 0) {
    throw std::runtime_error("encode_png: PNG encoding failed");
  }
  return png;
}

std::string png_data_uri(const Image& image) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::vector<std::uint8_t> png = encode_png(image);
  std::string uri = "data:image/png;base64,";
  uri.reserve(uri.size() + (png.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < png.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, png.size() - i);
    std::uint32_t v = std::uint32_t(png[i]) << 16;
    if (n > 1) v |= std::uint32_t(png[i + 1]) << 8;
    if (n > 2) v |= png[i + 2];
    uri += kDigits[(v >> 18) & 63];
    uri += kDigits[(v >> 12) & 63];
    uri += n > 1 ? kDigits[(v >> 6) & 63] : '=';
    uri += n > 2 ? kDigits[v & 63] : '=';
  }
  return uri;
}

Image decode_png(const std::vector<std::uint8_t>& bytes) {
  if (bytes.empty() || bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::runtime_error("decode_png: no PNG data");
  }
  int w = 0;
  int h = 0;
  int channels = 0;
  stbi_uc* pixels =
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &channels, 4);
  if (pixels == nullptr) {
    const char* reason = stbi_failure_reason();
    throw std::runtime_error(std::string("decode_png: ") +
                             (reason != nullptr ? reason : "malformed PNG"));
  }
  Image image;
  image.width = w;
  image.height = h;
  image.rgba.assign(pixels, pixels + 4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  stbi_image_free(pixels);
  return image;
}

Image side_by_side(const Image& left, const Image& right, const std::string& left_caption,
                   const std::string& right_caption, int gap, Rgba background) {
  if (gap < 0) throw std::invalid_argument("side_by_side: negative gap");
  const bool captions = !left_caption.empty() || !right_caption.empty();
  const int band = captions ? kCaptionScale * kTextDescentUnits + 2 * kCaptionPadding : 0;
  Image canvas(left.width + gap + right.width, band + std::max(left.height, right.height),
               background);
  blit(left, canvas, 0, band);
  blit(right, canvas, left.width + gap, band);
  const Rgba ink = text_color_for(background);
  draw_caption(canvas, left_caption, 0, left.width, ink);
  draw_caption(canvas, right_caption, left.width + gap, right.width, ink);
  return canvas;
}

}  // namespace sutura::render
