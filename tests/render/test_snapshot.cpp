// Off-screen snapshots through OSMesa: what a rendered scene must show.
//
// Set SUTURA_RENDER_TEST_OUTPUT to a directory to keep the rendered images as PNG files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "../../render/src/osmesa_library.hpp"
#include "sutura/render/renderer.hpp"
#include "test_meshes.hpp"

namespace sutura::render {
namespace {

using testing::square;
using testing::TestMesh;
using testing::tube;
using testing::uv_sphere;

constexpr int kW = 160;
constexpr int kH = 120;
constexpr Rgba kWhite = {255, 255, 255, 255};

void keep(const Image& image, const std::string& name) {
  const char* dir = std::getenv("SUTURA_RENDER_TEST_OUTPUT");
  if (dir == nullptr || *dir == '\0') return;
  const std::vector<std::uint8_t> png = encode_png(image);
  std::ofstream(std::filesystem::path(dir) / (name + ".png"), std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
}

Camera looking_at_origin(Point3 eye, Point3 up) {
  Camera c;
  c.eye = eye;
  c.target = {0.0f, 0.0f, 0.0f};
  c.up = up;
  return c;
}

// Pixel (column, row from the top) where `p` lands, using the renderer's own matrices.
std::array<int, 2> project(const Scene& scene, const Camera& c, int w, int h, const Point3& p) {
  const auto depth = depth_range(c, scene_bounds(scene));
  const auto v = view_matrix(c);
  const auto m =
      projection_matrix(c, static_cast<float>(w) / static_cast<float>(h), depth[0], depth[1]);
  std::array<float, 4> view{};
  std::array<float, 4> clip{};
  const float in[4] = {p[0], p[1], p[2], 1.0f};
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) view[r] += v[k * 4 + r] * in[k];
  }
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) clip[r] += m[k * 4 + r] * view[k];
  }
  const float x = (clip[0] / clip[3] * 0.5f + 0.5f) * static_cast<float>(w);
  const float y = (0.5f - clip[1] / clip[3] * 0.5f) * static_cast<float>(h);
  return {static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y))};
}

std::size_t distinct_colours(const Image& image) {
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    colours.insert(image.rgba[i] | image.rgba[i + 1] << 8 | image.rgba[i + 2] << 16);
  }
  return colours.size();
}

bool near_colour(Rgba a, Rgba b, int tolerance) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(int{a[k]} - int{b[k]}) > tolerance) return false;
  }
  return true;
}

int luminance(Rgba c) { return (2 * c[0] + 7 * c[1] + c[2]) / 10; }

class RenderSnapshot : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = create_offscreen_context();
    renderer_ = std::make_unique<Renderer>(*context_);
  }
  static void TearDownTestSuite() {
    renderer_.reset();
    context_.reset();
  }

  static Image render(const Scene& scene, const Camera& camera, int w = kW, int h = kH,
                      RenderOptions options = {}) {
    return renderer_->render(scene, camera, w, h, options);
  }

  /// A unit sphere coloured by height with a legend labelled `label`, rendered w x h with the
  /// legend, with its column kept free but no legend, and with neither; the camera is fitted
  /// to the part left of the column. Holds the mesh and scalars the scene only views.
  struct HeightLegend {
    TestMesh sphere = uv_sphere(1.0f, 32, 64);
    std::vector<float> z;
    Scene scene;
    Camera camera;
    int column = 0;
    Image with, space, without;
    HeightLegend(const std::string& label, int w, int h) {
      for (std::size_t v = 0; v < sphere.vertex_count(); ++v) z.push_back(sphere.positions[3 * v + 2]);
      scene.surfaces.push_back(sphere.surface());
      scene.surfaces[0].scalars = z;
      scene.color_map = ColorMap{ColorMapName::Viridis, -1.0f, 1.0f, label, true};
      column = legend_width(scene, w, h);
      camera = fit_camera(scene_bounds(scene), static_cast<float>(w - column) / h);
      with = render(scene, camera, w, h);
      RenderOptions no_legend;
      no_legend.draw_legend = false;
      without = render(scene, camera, w, h, no_legend);
      no_legend.legend_space = true;
      space = render(scene, camera, w, h, no_legend);
    }
    HeightLegend(const HeightLegend&) = delete;
    HeightLegend& operator=(const HeightLegend&) = delete;
  };

  static std::unique_ptr<GlContext> context_;
  static std::unique_ptr<Renderer> renderer_;
};

std::unique_ptr<GlContext> RenderSnapshot::context_;
std::unique_ptr<Renderer> RenderSnapshot::renderer_;

// Anti-aliasing within a memory budget: every sample costs llvmpipe 8 bytes, cleared per
// render, so a large render gets fewer samples (an 8192 x 8192 one: none).
TEST(RenderSamples, FullAntiAliasingUpTo4096SquaredThenFewerSamples) {
  EXPECT_EQ(render_samples(4, 1920, 1080, 4), 4);
  EXPECT_EQ(render_samples(4, 4096, 4096, 4), 4);
  EXPECT_EQ(render_samples(4, 4096, 4097, 4), 3);
  EXPECT_EQ(render_samples(4, 5792, 5792, 4), 2);
  EXPECT_EQ(render_samples(4, 8192, 4096, 4), 2);
  EXPECT_EQ(render_samples(4, 8192, 8192, 4), 1);
  EXPECT_EQ(render_samples(8, 640, 480, 4), 4);  // the GL limit
  EXPECT_EQ(render_samples(4, 640, 480, 0), 1);  // no multisampling at all
  EXPECT_EQ(render_samples(0, 640, 480, 4), 1);
  EXPECT_EQ(render_samples(1, 1, 1, 4), 1);
}

TEST_F(RenderSnapshot, SphereFillsTheCentreOnTheBackground) {
  const TestMesh sphere = uv_sphere(1.0f, 32, 64);
  Scene scene;
  scene.surfaces.push_back(sphere.surface());
  const Camera camera = fit_camera(scene_bounds(scene), static_cast<float>(kW) / kH);
  const Image image = render(scene, camera);
  keep(image, "sphere");
  ASSERT_EQ(image.width, kW);
  ASSERT_EQ(image.height, kH);
  const Rgba centre = image.pixel(kW / 2, kH / 2);
  EXPECT_NE(centre, kWhite);
  EXPECT_GT(centre[0], centre[1] + 20);  // the default salmon surface colour
  EXPECT_GT(centre[0], centre[2] + 20);
  EXPECT_EQ(image.pixel(0, 0), kWhite);
  EXPECT_EQ(image.pixel(kW - 1, 0), kWhite);
  EXPECT_EQ(image.pixel(0, kH - 1), kWhite);
  EXPECT_EQ(image.pixel(kW - 1, kH - 1), kWhite);
  EXPECT_GT(distinct_colours(image), 20u);  // shaded, not flat
}

TEST_F(RenderSnapshot, BackgroundColourIsSrgbEncoded) {
  Scene scene;
  scene.background = {0.2f, 0.4f, 0.6f};  // linear
  const Image image = render(scene, fit_camera(scene_bounds(scene), 1.0f), 8, 8);
  // sRGB encoding: 255 * (1.055 * c^(1/2.4) - 0.055), rounded.
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) EXPECT_EQ(image.pixel(x, y), (Rgba{124, 170, 203, 255}));
  }
}

TEST_F(RenderSnapshot, BackSideOfAnOpenSurfaceIsLitLikeTheFront) {
  const TestMesh plane = square(1.0f, 4);
  Scene scene;
  scene.surfaces.push_back(plane.surface());
  const Image front = render(scene, looking_at_origin({0.0f, 0.0f, 3.0f}, {0.0f, 1.0f, 0.0f}));
  const Image back = render(scene, looking_at_origin({0.0f, 0.0f, -3.0f}, {0.0f, 1.0f, 0.0f}));
  keep(back, "plane_back");
  const Rgba f = front.pixel(kW / 2, kH / 2);
  const Rgba b = back.pixel(kW / 2, kH / 2);
  EXPECT_NE(b, kWhite);
  EXPECT_GT(luminance(b), 100) << "back side looks unlit";
  EXPECT_TRUE(near_colour(f, b, 3));
}

TEST_F(RenderSnapshot, InsideOfATubeIsLit) {
  const TestMesh pipe = tube(1.0f, 6.0f, 24, 48);
  Scene scene;
  scene.surfaces.push_back(pipe.surface());
  // From inside the tube, off axis, looking along it: only back faces are visible.
  Camera camera = looking_at_origin({-2.5f, 0.0f, 0.3f}, {0.0f, 0.0f, 1.0f});
  camera.target = {2.0f, 0.0f, 0.3f};
  const Image image = render(scene, camera);
  keep(image, "tube_inside");
  int lit = 0;
  for (int x = 0; x < kW; x += 4) lit += luminance(image.pixel(x, kH / 8)) > 60 ? 1 : 0;
  EXPECT_GT(lit, kW / 4 / 2);
}

// A clip plane through the axis of a tube, facing the camera, removes the near wall and what
// lies on it (a suture line, a marker): the inside of the far wall shows where the near wall
// was. A plane across the top removes both walls there: background.
TEST_F(RenderSnapshot, AClipPlaneCutsAwayItsSideAndShowsTheInside) {
  const TestMesh pipe = tube(1.0f, 6.0f, 24, 48);
  Scene scene;
  scene.surfaces.push_back(pipe.surface());
  scene.surfaces[0].color = {0.2f, 0.4f, 0.9f};
  PolylineItem seam;  // along the near wall, y = -1
  seam.points = {{-2.0f, -1.0f, 0.0f}, {2.0f, -1.0f, 0.0f}};
  seam.color = {1.0f, 0.0f, 0.0f};
  seam.width_px = 5.0f;
  scene.polylines.push_back(seam);
  PointsItem probe;
  probe.points = {{-1.0f, -1.0f, 0.5f}};
  probe.color = {0.0f, 1.0f, 0.0f};
  probe.size_px = 9.0f;
  scene.points.push_back(probe);
  const Camera camera = looking_at_origin({0.0f, -6.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  const Image whole = render(scene, camera);
  const auto seam_px = project(scene, camera, kW, kH, {1.0f, -1.0f, 0.0f});
  const auto probe_px = project(scene, camera, kW, kH, probe.points[0]);
  ASSERT_TRUE(near_colour(whole.pixel(seam_px[0], seam_px[1]), {255, 0, 0, 255}, 10));
  ASSERT_TRUE(near_colour(whole.pixel(probe_px[0], probe_px[1]), {0, 255, 0, 255}, 10));

  scene.clip = ClipPlane{{0.0f, 0.0f, 0.0f}, {0.0f, -3.0f, 0.0f}};  // not unit length
  const Image cut = render(scene, camera);
  keep(cut, "clip_near_half");
  for (const auto& px : {seam_px, probe_px}) {
    const Rgba c = cut.pixel(px[0], px[1]);
    EXPECT_NE(c, kWhite);                               // the far wall, seen from inside
    EXPECT_GT(int{c[2]}, int{c[0]} + 40) << px[0];      // the tube's blue, not the seam's red
    EXPECT_GT(int{c[2]}, int{c[1]} + 20) << px[0];      // nor the probe's green
  }
  EXPECT_NE(cut.rgba, whole.rgba);

  scene.clip = ClipPlane{{0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, 1.0f}};
  const Image top = render(scene, camera);
  keep(top, "clip_top");
  const auto high = project(scene, camera, kW, kH, {0.0f, -0.6f, 0.8f});
  const auto low = project(scene, camera, kW, kH, {0.0f, -0.6f, -0.8f});
  EXPECT_EQ(top.pixel(high[0], high[1]), kWhite);
  EXPECT_EQ(top.pixel(low[0], low[1]), whole.pixel(low[0], low[1]));
  EXPECT_EQ(top.rgba, render(scene, camera).rgba);  // deterministic

  scene.clip = ClipPlane{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
  EXPECT_THROW(render(scene, camera), std::invalid_argument);
  scene.clip = ClipPlane{{std::nanf(""), 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
  EXPECT_THROW(render(scene, camera), std::invalid_argument);
  scene.clip.reset();
  EXPECT_EQ(render(scene, camera).rgba, whole.rgba);  // the renderer is unharmed
}

TEST_F(RenderSnapshot, ScalarColourMapsGiveTheirLowAndHighColours) {
  const TestMesh plane = square(1.0f, 32);
  std::vector<float> x_scalars;
  for (std::size_t v = 0; v < plane.vertex_count(); ++v)
    x_scalars.push_back(plane.positions[3 * v]);
  Scene scene;
  scene.surfaces.push_back(plane.surface());
  scene.surfaces[0].scalars = x_scalars;
  const Camera camera = looking_at_origin({0.0f, 0.0f, 3.0f}, {0.0f, 1.0f, 0.0f});
  RenderOptions options;
  options.draw_legend = false;

  const auto ends = [&](ColorMapName name, const char* file) {
    scene.color_map = ColorMap{name, -1.0f, 1.0f, "x", true};
    const Image image = render(scene, camera, kW, kH, options);
    keep(image, file);
    return std::array<Rgba, 2>{image.pixel(kW / 4, kH / 2), image.pixel(3 * kW / 4, kH / 2)};
  };
  const auto coolwarm = ends(ColorMapName::Coolwarm, "map_coolwarm");
  EXPECT_GT(coolwarm[0][2], coolwarm[0][0] + 40);  // low: blue
  EXPECT_GT(coolwarm[1][0], coolwarm[1][2] + 40);  // high: red
  const auto viridis = ends(ColorMapName::Viridis, "map_viridis");
  EXPECT_GT(viridis[0][2], viridis[0][1] + 20);  // low: violet-blue
  EXPECT_GT(viridis[1][1], viridis[1][2] + 40);  // high: green-yellow
  EXPECT_GT(viridis[1][0], viridis[1][2]);
  const auto jet = ends(ColorMapName::Jet, "map_jet");
  EXPECT_GT(jet[0][2], jet[0][0] + 60);  // low: blue
  EXPECT_GT(jet[1][0], jet[1][2] + 60);  // high: red-orange

  // Colour comes from the map, not from the surface colour.
  scene.surfaces[0].color = {0.0f, 1.0f, 0.0f};
  EXPECT_EQ(ends(ColorMapName::Coolwarm, "map_coolwarm_again"), coolwarm);
}

TEST_F(RenderSnapshot, PolylineOnTheSurfaceShowsAlongItsPathAndHidesBehindIt) {
  const TestMesh sphere = uv_sphere(1.0f, 32, 64);
  const Camera camera = looking_at_origin({0.0f, -4.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  // A meridian in the plane x = 0: the front half (y < 0) faces the camera.
  PolylineItem front;
  PolylineItem back;
  for (int i = 0; i <= 48; ++i) {
    const float a = std::numbers::pi_v<float> * static_cast<float>(i) / 48.0f;
    front.points.push_back({0.0f, -std::sin(a), std::cos(a)});
    back.points.push_back({0.0f, std::sin(a), std::cos(a)});
  }
  front.color = back.color = {0.0f, 1.0f, 0.0f};
  front.width_px = back.width_px = 4.0f;

  Scene scene;
  scene.surfaces.push_back(sphere.surface());
  scene.polylines.push_back(front);
  const Image image = render(scene, camera);
  keep(image, "polyline_front");
  for (const float z : {-0.7f, -0.35f, 0.0f, 0.35f, 0.7f}) {
    const auto px = project(scene, camera, kW, kH, {0.0f, -std::sqrt(1.0f - z * z), z});
    const Rgba on = image.pixel(px[0], px[1]);
    EXPECT_GT(on[1], 200) << "z " << z;
    EXPECT_LT(on[0], 90) << "z " << z;
    const Rgba beside = image.pixel(px[0] + 12, px[1]);
    EXPECT_LT(beside[1], 200) << "z " << z;  // the surface, not the line
  }

  scene.polylines = {back};
  const Image hidden = render(scene, camera);
  for (const float z : {-0.35f, 0.0f, 0.35f}) {
    const auto px = project(scene, camera, kW, kH, {0.0f, -std::sqrt(1.0f - z * z), z});
    EXPECT_GT(hidden.pixel(px[0], px[1])[0], 150) << "back polyline shows through at z " << z;
  }
}

TEST_F(RenderSnapshot, PolylineReachingBehindTheCameraIsClippedAtTheNearPlane) {
  const Camera camera = looking_at_origin({0.0f, -4.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  PolylineItem line;
  line.points = {{-1.0f, -8.0f, -0.2f}, {1.0f, 2.0f, 0.2f}};  // starts 4 units behind the eye
  line.color = {0.0f, 0.0f, 1.0f};
  line.width_px = 5.0f;
  Scene scene;
  scene.polylines.push_back(line);
  const Image image = render(scene, camera);
  keep(image, "polyline_near_clip");
  for (const float t : {0.5f, 0.7f, 1.0f}) {  // visible part: y from -3 to 2
    const Point3 p = {-1.0f + 2.0f * t, -8.0f + 10.0f * t, -0.2f + 0.4f * t};
    const auto px = project(scene, camera, kW, kH, p);
    EXPECT_TRUE(near_colour(image.pixel(px[0], px[1]), {0, 0, 255, 255}, 10)) << "t " << t;
  }
  // A thin line, not a smear: most of the image stays background.
  int background = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) background += image.rgba[i] == 255 ? 1 : 0;
  EXPECT_GT(background, kW * kH * 3 / 4);
}

TEST_F(RenderSnapshot, PointsShowOnTheSurfaceAndInFreeSpace) {
  const TestMesh sphere = uv_sphere(1.0f, 32, 64);
  const Camera camera = looking_at_origin({0.0f, -4.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  Scene scene;
  scene.surfaces.push_back(sphere.surface());
  PointsItem points;
  points.points = {{0.0f, -1.0f, 0.0f}, {1.4f, 0.0f, 0.9f}};
  points.color = {1.0f, 0.0f, 1.0f};
  points.size_px = 10.0f;
  scene.points.push_back(points);
  const Image image = render(scene, camera);
  keep(image, "points");
  for (const Point3& p : points.points) {
    const auto px = project(scene, camera, kW, kH, p);
    EXPECT_TRUE(near_colour(image.pixel(px[0], px[1]), {255, 0, 255, 255}, 8)) << p[0];
  }
  const auto free_point = project(scene, camera, kW, kH, points.points[1]);
  EXPECT_EQ(image.pixel(free_point[0] + 8, free_point[1]), kWhite);      // round, of limited size
  EXPECT_EQ(image.pixel(free_point[0] + 5, free_point[1] + 5), kWhite);  // corner of the square
}

TEST_F(RenderSnapshot, LegendTakesAColumnOnTheRightAndTheSceneIsDrawnLeftOfIt) {
  const int w = 320;
  const int h = 240;
  HeightLegend legend("height [mm]", w, h);
  const Image& with = legend.with;
  keep(with, "legend");
  ASSERT_GT(legend.column, 0);
  ASSERT_LE(legend.column, w / 2);
  const int left = w - legend.column;
  const auto background = legend.space.pixel(0, 0);
  int changed = 0, dark = 0, sphere_left = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (x < left) {
        // Left of the column: the scene, exactly as drawn with the column kept free.
        EXPECT_EQ(with.pixel(x, y), legend.space.pixel(x, y)) << x << "," << y;
        sphere_left += legend.space.pixel(x, y) != background ? 1 : 0;
        continue;
      }
      // In the column: nothing of the scene, only the legend.
      EXPECT_EQ(legend.space.pixel(x, y), background) << "scene pixel under the legend at " << x << "," << y;
      if (with.pixel(x, y) == background) continue;
      ++changed;
      dark += luminance(with.pixel(x, y)) < 60 ? 1 : 0;
    }
  }
  EXPECT_GT(changed, 400);
  EXPECT_GT(dark, 100);  // frame and text
  EXPECT_GT(sphere_left, 5000);
  // Without the legend the scene takes the whole width.
  EXPECT_NE(legend.without.rgba, legend.space.rgba);
  legend.scene.color_map->show_legend = false;
  EXPECT_EQ(legend_width(legend.scene, w, h), 0);
  EXPECT_EQ(render(legend.scene, legend.camera, w, h).rgba, legend.without.rgba);
}

// Each half of a side-by-side window is tall and narrow (501 x 900 in the subclavian flap's
// GUI test): at the font of its height the column for this label and these numbers would take
// more than half the width, so a smaller font is used rather than leaving the colours unexplained.
TEST_F(RenderSnapshot, ANarrowViewGetsItsLegendInASmallerFont) {
  const int w = 501, h = 900;
  HeightLegend legend("max principal membrane strain [-]", w, h);
  legend.scene.color_map->min = -0.005817f;
  legend.scene.color_map->max = 0.5693f;
  const int narrow = legend_width(legend.scene, w, h);
  ASSERT_GT(narrow, 0);
  EXPECT_LE(narrow, w / 2);
  // The same legend in a wide view of the same height keeps the height's (larger) font.
  EXPECT_GT(legend_width(legend.scene, 3 * w, h), narrow);
  const Image image = render(legend.scene, legend.camera, w, h);
  keep(image, "legend_narrow");
  const auto background = image.pixel(0, 0);
  int dark = 0;
  for (int y = 0; y < h; ++y)
    for (int x = w - narrow; x < w; ++x) dark += luminance(image.pixel(x, y)) < 60 ? 1 : 0;
  EXPECT_GT(dark, 100);  // frame and text drawn
  EXPECT_EQ(image.pixel(w - narrow, 0), background);
}

TEST_F(RenderSnapshot, LongLegendLabelWrapsInsteadOfCrossingThePicture) {
  // A label several times wider than a third of the picture is wrapped at its spaces: every
  // legend pixel stays in the right third (plus the margin), and the label takes more than
  // one line above the bar.
  const int w = 640;
  const int h = 480;
  const HeightLegend legend("max principal membrane strain [-] (top 0.5 % clipped)", w, h);
  const Image& with = legend.with;
  keep(with, "legend_long_label");
  int leftmost = w, top = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (with.pixel(x, y) != legend.space.pixel(x, y)) leftmost = std::min(leftmost, x), top = std::min(top, y);
  EXPECT_GE(leftmost, w - w / 3 - 12) << "the label runs into the picture";
  EXPECT_GE(leftmost, w - legend.column) << "the label leaves the legend's column";
  // The bar starts at 3/10 of the height; two or more label lines reach above it by more
  // than one line (12 font units at scale 1 for 480 px).
  EXPECT_LT(top, (h - h * 2 / 5) / 2 - 2 * 12);
}

TEST_F(RenderSnapshot, WireframeOverlayDrawsEdges) {
  const TestMesh plane = square(1.0f, 8);
  Scene scene;
  scene.surfaces.push_back(plane.surface());
  scene.surfaces[0].wire_color = {0.0f, 0.0f, 0.0f};
  const Camera camera = looking_at_origin({0.5f, -1.0f, 3.0f}, {0.0f, 1.0f, 0.0f});
  const auto count_dark = [](const Image& image) {
    int dark = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
      dark += image.rgba[i] < 60 && image.rgba[i + 1] < 60 && image.rgba[i + 2] < 60 ? 1 : 0;
    }
    return dark;
  };
  EXPECT_EQ(count_dark(render(scene, camera)), 0);
  scene.surfaces[0].wireframe = true;
  const Image wired = render(scene, camera);
  keep(wired, "wireframe");
  EXPECT_GT(count_dark(wired), 300);
}

TEST_F(RenderSnapshot, MultisamplingBlendsEdgeColours) {
  const TestMesh sphere = uv_sphere(1.0f, 32, 64);
  Scene scene;
  scene.surfaces.push_back(sphere.surface());
  PolylineItem line;
  line.points = {{-1.5f, 0.0f, -1.2f}, {1.5f, 0.0f, 1.3f}};
  scene.polylines.push_back(line);
  const Camera camera = fit_camera(scene_bounds(scene), static_cast<float>(kW) / kH);
  RenderOptions aliased;
  aliased.samples = 1;
  const Image hard = render(scene, camera, kW, kH, aliased);
  const Image smooth = render(scene, camera);
  keep(hard, "msaa_off");
  keep(smooth, "msaa_on");
  EXPECT_GT(distinct_colours(smooth), distinct_colours(hard) + 20);  // ~390 vs ~460 here
}

TEST_F(RenderSnapshot, SizesOutsideTheRangeThrowGlError) {
  Scene scene;
  const Camera camera;
  for (const auto& [w, h] :
       {std::pair{0, 10}, std::pair{10, 0}, std::pair{-3, 5}, std::pair{8193, 4}}) {
    try {
      render(scene, camera, w, h);
      ADD_FAILURE() << w << "x" << h << " did not throw";
    } catch (const GlError& e) {
      EXPECT_NE(std::string(e.what()).find(std::to_string(w) + "x" + std::to_string(h)),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(renderer_->draw(scene, camera, 1, 9000), GlError);
  const Image tiny = render(scene, camera, 1, 1);  // the bounds themselves are fine
  EXPECT_EQ(tiny.rgba.size(), 4u);
}

TEST_F(RenderSnapshot, InconsistentSurfaceArraysAreRejectedWithoutBreakingTheRenderer) {
  const TestMesh plane = square(1.0f, 2);
  Scene scene;
  scene.surfaces.push_back(plane.surface());
  const std::vector<std::uint32_t> bad = {0, 1, 99};
  scene.surfaces[0].triangles = bad;
  const Camera camera = looking_at_origin({0.0f, 0.0f, 3.0f}, {0.0f, 1.0f, 0.0f});
  EXPECT_THROW(render(scene, camera), std::invalid_argument);
  const std::vector<float> too_few_scalars = {1.0f};
  scene.surfaces[0] = plane.surface();
  scene.surfaces[0].scalars = too_few_scalars;
  EXPECT_THROW(render(scene, camera), std::invalid_argument);
  scene.surfaces[0] = plane.surface();
  EXPECT_NE(render(scene, camera).pixel(kW / 2, kH / 2), kWhite);
}

TEST_F(RenderSnapshot, RenderingIsDeterministic) {
  const TestMesh sphere = uv_sphere(1.0f, 24, 48);
  std::vector<float> scalars;
  for (std::size_t v = 0; v < sphere.vertex_count(); ++v)
    scalars.push_back(sphere.positions[3 * v]);
  Scene scene;
  scene.surfaces.push_back(sphere.surface());
  scene.surfaces[0].scalars = scalars;
  scene.surfaces[0].wireframe = true;
  scene.color_map = ColorMap{ColorMapName::Coolwarm, -1.0f, 1.0f, "x", true};
  scene.polylines.push_back(
      {{{-1, -1, 0}, {0, -1.2f, 0.5f}, {1, -1, 0}}, {0.1f, 0.3f, 0.9f}, 3.0f, true});
  scene.points.push_back({{{0, -1, 0}, {0.5f, -0.8f, 0.3f}}, {0.9f, 0.8f, 0.1f}, 8.0f});
  const Camera camera = fit_camera(scene_bounds(scene), 4.0f / 3.0f);
  const Image first = render(scene, camera, 200, 150);
  const Image second = render(scene, camera, 200, 150);
  EXPECT_EQ(first.rgba, second.rgba);
  Renderer fresh(*context_);
  EXPECT_EQ(fresh.render(scene, camera, 200, 150).rgba, first.rgba);
  EXPECT_EQ(encode_png(first), encode_png(second));
  keep(first, "everything");
}

TEST(RenderWindow, WithoutADisplayThrowsGlError) {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  const std::optional<std::string> saved_x11 =
      x11 != nullptr ? std::optional<std::string>(x11) : std::nullopt;
  const std::optional<std::string> saved_wayland =
      wayland != nullptr ? std::optional<std::string>(wayland) : std::nullopt;
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  try {
    WindowContext window(64, 64, "test", false);
    ADD_FAILURE() << "a window opened without a display";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("display"), std::string::npos) << e.what();
  }
  if (saved_x11) setenv("DISPLAY", saved_x11->c_str(), 1);
  if (saved_wayland) setenv("WAYLAND_DISPLAY", saved_wayland->c_str(), 1);
}

}  // namespace
}  // namespace sutura::render

// OSMesa is loaded when the first off-screen context is made; without it, the error names
// the library and the Debian package.
TEST(RenderOsMesa, AMissingLibraryIsNamedWithItsPackage) {
  try {
    (void)sutura::render::detail::load_osmesa("libOSMesa-not-here.so.8");
    ADD_FAILURE() << "a missing library loaded";
  } catch (const sutura::render::GlError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("libOSMesa-not-here.so.8"), std::string::npos) << m;
    EXPECT_NE(m.find("libosmesa6"), std::string::npos) << m;
  }
  // A library without the entry points (libm has none of them) is refused by name too.
  try {
    (void)sutura::render::detail::load_osmesa("libm.so.6");
    ADD_FAILURE() << "libm was taken for OSMesa";
  } catch (const sutura::render::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("OSMesaCreateContextAttribs"), std::string::npos) << e.what();
  }
  EXPECT_NE(sutura::render::detail::osmesa().get_proc_address, nullptr);  // the real one
}
