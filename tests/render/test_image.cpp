// Image pixels, PNG round trip and side-by-side composition.
#include <gtest/gtest.h>

#include <stdexcept>

#include "sutura/render/image.hpp"

namespace sutura::render {
namespace {

Image gradient_image(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.set_pixel(x, y,
                      {static_cast<std::uint8_t>(x * 7), static_cast<std::uint8_t>(y * 11),
                       static_cast<std::uint8_t>((x + y) * 3), static_cast<std::uint8_t>(255 - x)});
    }
  }
  return image;
}

bool is_dark(Rgba c) { return c[0] < 100 && c[1] < 100 && c[2] < 100; }

TEST(RenderImage, ConstructorFillsAndPixelAccessIsBoundsChecked) {
  Image image(3, 2, {1, 2, 3, 4});
  EXPECT_EQ(image.rgba.size(), 3u * 2u * 4u);
  EXPECT_EQ(image.pixel(2, 1), (Rgba{1, 2, 3, 4}));
  image.set_pixel(2, 1, {9, 8, 7, 6});
  EXPECT_EQ(image.pixel(2, 1), (Rgba{9, 8, 7, 6}));
  EXPECT_EQ(image.pixel(1, 1), (Rgba{1, 2, 3, 4}));
  EXPECT_THROW((void)image.pixel(3, 0), std::out_of_range);
  EXPECT_THROW((void)image.pixel(0, 2), std::out_of_range);
  EXPECT_THROW((void)image.pixel(-1, 0), std::out_of_range);
  EXPECT_THROW(image.set_pixel(0, -1, {}), std::out_of_range);
  EXPECT_THROW(image.set_pixel(3, 1, {}), std::out_of_range);
  EXPECT_THROW(Image(-1, 4), std::invalid_argument);
}

TEST(RenderImage, PngRoundTripPreservesEveryPixel) {
  const Image original = gradient_image(37, 23);
  const std::vector<std::uint8_t> png = encode_png(original);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png[1], 'P');
  EXPECT_EQ(png[2], 'N');
  EXPECT_EQ(png[3], 'G');
  const Image decoded = decode_png(png);
  EXPECT_EQ(decoded.width, 37);
  EXPECT_EQ(decoded.height, 23);
  EXPECT_EQ(decoded.rgba, original.rgba);
}

// Renders are opaque: their PNG is RGB (colour type 2, byte 25), and decodes to the same
// pixels with alpha 255; an image with any other alpha stays RGBA (type 6).
TEST(RenderImage, OpaqueImagesAreWrittenAsRgb) {
  Image opaque = gradient_image(37, 23);
  for (std::size_t i = 3; i < opaque.rgba.size(); i += 4) opaque.rgba[i] = 255;
  const std::vector<std::uint8_t> png = encode_png(opaque);
  ASSERT_GT(png.size(), 26u);
  EXPECT_EQ(png[25], 2);
  EXPECT_EQ(decode_png(png).rgba, opaque.rgba);
  Image one_translucent = opaque;
  one_translucent.rgba.back() = 254;
  const std::vector<std::uint8_t> rgba_png = encode_png(one_translucent);
  ASSERT_GT(rgba_png.size(), 26u);
  EXPECT_EQ(rgba_png[25], 6);
  EXPECT_EQ(decode_png(rgba_png).rgba, one_translucent.rgba);
}

TEST(RenderImage, PngErrors) {
  EXPECT_THROW(decode_png({}), std::runtime_error);
  EXPECT_THROW(decode_png({1, 2, 3, 4, 5, 6, 7, 8, 9}), std::runtime_error);
  EXPECT_THROW(encode_png(Image{}), std::invalid_argument);
}

TEST(RenderImage, SideBySideWithoutCaptionsPlacesImagesAndGap) {
  const Image left(10, 6, {255, 0, 0, 255});
  const Image right(7, 9, {0, 0, 255, 255});
  const Rgba background = {0, 255, 0, 255};
  const Image both = side_by_side(left, right, "", "", 5, background);
  EXPECT_EQ(both.width, 10 + 5 + 7);
  EXPECT_EQ(both.height, 9);
  EXPECT_EQ(both.pixel(0, 0), left.pixel(0, 0));
  EXPECT_EQ(both.pixel(9, 5), left.pixel(9, 5));
  EXPECT_EQ(both.pixel(9, 6), background);   // below the shorter left image
  EXPECT_EQ(both.pixel(12, 4), background);  // in the gap
  EXPECT_EQ(both.pixel(15, 0), right.pixel(0, 0));
  EXPECT_EQ(both.pixel(21, 8), right.pixel(6, 8));
}

TEST(RenderImage, SideBySideCaptionsDrawDarkTextInABandAbove) {
  const Image left(120, 40, {255, 255, 255, 255});
  const Image right(120, 50, {255, 255, 255, 255});
  const Image both = side_by_side(left, right, "Before", "After");
  EXPECT_EQ(both.width, 120 + 8 + 120);
  const int band = both.height - 50;
  ASSERT_GT(band, 10);
  // The images sit below the band, unchanged.
  EXPECT_EQ(both.pixel(0, band), (Rgba{255, 255, 255, 255}));
  int dark_left = 0;
  int dark_right = 0;
  int dark_below = 0;
  for (int y = 0; y < both.height; ++y) {
    for (int x = 0; x < both.width; ++x) {
      if (!is_dark(both.pixel(x, y))) continue;
      if (y >= band)
        ++dark_below;
      else if (x < 120)
        ++dark_left;
      else if (x >= 128)
        ++dark_right;
    }
  }
  EXPECT_GT(dark_left, 30);
  EXPECT_GT(dark_right, 30);
  EXPECT_EQ(dark_below, 0);
  // Captions are centred over their image: no ink near the outer edges.
  for (int y = 0; y < band; ++y) {
    EXPECT_FALSE(is_dark(both.pixel(2, y)));
    EXPECT_FALSE(is_dark(both.pixel(both.width - 3, y)));
  }
}

TEST(RenderImage, CaptionsAreLightOnDarkBackgrounds) {
  const Image tile(80, 20, {0, 0, 0, 255});
  const Image both = side_by_side(tile, tile, "L", "", 4, {0, 0, 0, 255});
  int light = 0;
  for (std::size_t i = 0; i < both.rgba.size(); i += 4) light += both.rgba[i] > 200 ? 1 : 0;
  EXPECT_GT(light, 10);
}

}  // namespace
}  // namespace sutura::render
