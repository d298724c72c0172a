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
  Image(int w, int h, Rgba fill = {255, 255, 255, 255});
  [[nodiscard]] Rgba pixel(int x, int y) const;
  void set_pixel(int x, int y, Rgba c);
};

/// PNG file content of `image` (no file is written; callers write it atomically).
std::vector<std::uint8_t> encode_png(const Image& image);
/// Decodes PNG bytes (tests and tools); throws std::runtime_error on malformed data.
Image decode_png(const std::vector<std::uint8_t>& bytes);

/// Places `left` and `right` next to each other separated by `gap` pixels of `background`,
/// each with an optional caption drawn above it (e.g. "Before", "After"). Images of different
/// heights are top-aligned on the background.
Image side_by_side(const Image& left, const Image& right, const std::string& left_caption = {},
                   const std::string& right_caption = {}, int gap = 8,
                   Rgba background = {255, 255, 255, 255});

}  // namespace sutura::render
