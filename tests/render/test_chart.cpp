// Line charts drawn on the CPU (design_patch's plot).
#include "sutura/render/chart.hpp"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace sutura::render {
namespace {

Chart diagonal() {
  Chart c;  // 960 x 600: plot area x 100..860, y 84..524
  c.title = std::string("Lumen against width");
  c.x_label.assign("width [mm]");
  c.y_label.assign("area [mm2]");
  ChartSeries s;
  s.label = "area";
  s.points = {{0.0, 0.0}, {10.0, 10.0}};
  s.color = {200, 30, 30, 255};
  c.series.push_back(s);
  c.bands.push_back({2.0, 3.0, false, {180, 240, 180, 255}});
  return c;
}

// Both axes run over [-0.5, 10.5] (5 % to spare): (5, 5) is at the plot area's centre, (8.3, 2.5)
// in the band below the diagonal, and the top-right corner's pixel off the line is white.
TEST(Chart, MapsValuesIntoThePlotArea) {
  const Image im = draw_chart(diagonal());
  ASSERT_EQ(im.width, 960);
  ASSERT_EQ(im.height, 600);
  const Rgba red{200, 30, 30, 255};
  EXPECT_EQ(im.pixel(480, 304), red);
  const int x8 = static_cast<int>(std::lround(100 + 8.8 / 11 * 760));  // off the grid line at 8
  const int y25 = static_cast<int>(std::lround(524 - 3.0 / 11 * 440));
  EXPECT_EQ(im.pixel(x8, y25), (Rgba{180, 240, 180, 255}));
  EXPECT_EQ(im.pixel(850, 98), (Rgba{255, 255, 255, 255}));
  EXPECT_EQ(draw_chart(diagonal()).rgba, im.rgba) << "deterministic";
}

TEST(Chart, ASecondAxisScalesItsOwnSeries) {
  Chart c = diagonal();
  ChartSeries s;
  s.label = "bulge";
  s.points = {{0.0, 100.0}, {10.0, 100.0}};  // a flat line at the middle of its own axis
  s.color = {20, 20, 200, 255};
  s.right_axis = true;
  c.series.push_back(s);
  const Image im = draw_chart(c);
  EXPECT_EQ(im.pixel(300, 304), (Rgba{20, 20, 200, 255}));
}

// Values a few ulps apart, or all equal, still get axes to step through (no endless ticks).
TEST(Chart, NearlyEqualValuesGetARange) {
  Chart c = diagonal();
  c.bands.clear();
  c.series[0].points = {{0.0, 1.0}, {1.0, std::nextafter(1.0, 2.0)}};
  EXPECT_EQ(draw_chart(c).width, 960);
  c.series[0].points = {{3.0, 5.0}, {3.0, 5.0}};
  EXPECT_EQ(draw_chart(c).width, 960);
  c.series[0].points = {{0.0, -1e308}, {1.0, 1e308}};
  EXPECT_THROW((void)draw_chart(c), std::invalid_argument);
}

TEST(Chart, RefusesBadCharts) {
  Chart c = diagonal();
  c.width = 100;
  EXPECT_THROW((void)draw_chart(c), std::invalid_argument);
  c = diagonal();
  c.series.clear();
  EXPECT_THROW((void)draw_chart(c), std::invalid_argument);
  c = diagonal();
  c.series[0].points.clear();
  EXPECT_THROW((void)draw_chart(c), std::invalid_argument);
  c = diagonal();
  c.series[0].points[1][1] = std::nan("");
  EXPECT_THROW((void)draw_chart(c), std::invalid_argument);
}

}  // namespace
}  // namespace sutura::render
