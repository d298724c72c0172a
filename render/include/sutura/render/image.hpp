#pragma once
// RGBA8 images, PNG encoding (stb_image_write) and side-by-side composition.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sutura::render {

using Rgba = std::array<std::uint8_t, 4>;

/// Row-major RGBA8 image, top row first (as PNG stores it).
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< 4 * width * height bytes

  Image() = default;
  /// Throws std::invalid_argument for a negative size.
  Image(int w, int h, Rgba fill = {255, 255, 255, 255});
  /// Pixel access, (0, 0) top-left; throw std::out_of_range outside the image.
  [[nodiscard]] Rgba pixel(int x, int y) const;
  void set_pixel(int x, int y, Rgba c);
};

/// PNG file content of `image` (no file is written; callers write it atomically).
/// Throws std::invalid_argument for an empty or inconsistent image. An image whose alpha is
/// 255 everywhere is written as RGB (colour type 2), any other as RGBA (type 6). Uses
/// stb_image_write with the Sub row filter at compression level 5 (set once, process-wide,
/// in stb's globals). Cost: about 0.1 s for a 1920x1080 render, as much as rendering it.
std::vector<std::uint8_t> encode_png(const Image& image);
/// "data:image/png;base64,..." of encode_png(image) (RFC 4648 base64 with padding): a picture
/// inside an HTML or SVG file. Same errors as encode_png.
std::string png_data_uri(const Image& image);

/// Decodes PNG bytes (tests and tools); throws std::runtime_error on malformed data.
Image decode_png(const std::vector<std::uint8_t>& bytes);

/// Places `left` and `right` next to each other separated by `gap` pixels of `background`,
/// each with an optional caption drawn above it (e.g. "Before", "After"). Images of different
/// heights are top-aligned on the background. Captions use a built-in bitmap font (ASCII;
/// other bytes show as '?'), 2 px per font unit, centred and clipped to their image's
/// width, dark on light backgrounds and light on dark ones; with any caption the images
/// sit below a 30-pixel caption band. Throws std::invalid_argument for a negative gap.
Image side_by_side(const Image& left, const Image& right, const std::string& left_caption = {},
                   const std::string& right_caption = {}, int gap = 8,
                   Rgba background = {255, 255, 255, 255});

}  // namespace sutura::render
