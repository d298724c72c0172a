// Camera fitting, view/projection matrices and scene bounds.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "sutura/render/camera.hpp"

namespace sutura::render {
namespace {

using Mat4 = std::array<float, 16>;

std::array<float, 4> transform(const Mat4& m, const std::array<float, 4>& v) {
  std::array<float, 4> out{};
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) out[row] += m[col * 4 + row] * v[col];  // column-major
  }
  return out;
}

std::array<float, 3> to_ndc(const Camera& c, float aspect, float near_z, float far_z,
                            const Point3& p) {
  const auto clip = transform(projection_matrix(c, aspect, near_z, far_z),
                              transform(view_matrix(c), {p[0], p[1], p[2], 1.0f}));
  return {clip[0] / clip[3], clip[1] / clip[3], clip[2] / clip[3]};
}

TEST(RenderCamera, FitKeepsAllBoundsCornersInsideNdc) {
  const std::array<Point3, 2> bounds = {Point3{-1.0f, 2.0f, -0.5f}, Point3{3.0f, 2.5f, 4.0f}};
  const Point3 directions[] = {{-0.4f, 1.0f, -0.35f},
                               {0.0f, 0.0f, -1.0f},
                               {1.0f, 0.0f, 0.0f},
                               {0.3f, -0.2f, 0.9f},
                               {0.0f, 1.0f, 0.0f}};
  for (const float aspect : {0.5f, 1.0f, 16.0f / 9.0f, 3.0f}) {
    for (const Point3& dir : directions) {
      const Camera c = fit_camera(bounds, aspect, dir);
      const auto depth = depth_range(c, bounds);
      ASSERT_GT(depth[0], 0.0f);
      ASSERT_GT(depth[1], depth[0]);
      float max_extent = 0.0f;
      for (int corner = 0; corner < 8; ++corner) {
        const Point3 p = {bounds[corner & 1][0], bounds[(corner >> 1) & 1][1],
                          bounds[(corner >> 2) & 1][2]};
        const auto ndc = to_ndc(c, aspect, depth[0], depth[1], p);
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(std::abs(ndc[k]), 1.0f)
              << "aspect " << aspect << " corner " << corner << " axis " << k;
        }
        max_extent = std::max({max_extent, std::abs(ndc[0]), std::abs(ndc[1])});
      }
      // Fitted, not lost in the distance: the box (thin along y, so its bounding sphere is
      // loose) still spans a good part of the view.
      EXPECT_GT(max_extent, 0.3f) << "aspect " << aspect;
    }
  }
}

TEST(RenderCamera, FitLooksAtTheBoundsCentreAlongTheViewDirection) {
  const std::array<Point3, 2> bounds = {Point3{0.0f, 0.0f, 0.0f}, Point3{2.0f, 2.0f, 2.0f}};
  const Camera c = fit_camera(bounds, 1.0f, {0.0f, 2.0f, 0.0f});
  EXPECT_FLOAT_EQ(c.target[0], 1.0f);
  EXPECT_FLOAT_EQ(c.target[1], 1.0f);
  EXPECT_FLOAT_EQ(c.target[2], 1.0f);
  EXPECT_FLOAT_EQ(c.eye[0], 1.0f);
  EXPECT_LT(c.eye[1], -1.0f);  // in front of the box, looking along +y
  EXPECT_FLOAT_EQ(c.eye[2], 1.0f);
}

TEST(RenderCamera, ExplicitCameraMatchesHandComputedMatrices) {
  Camera c;
  c.eye = {0.0f, 0.0f, 5.0f};
  c.target = {0.0f, 0.0f, 0.0f};
  c.up = {0.0f, 1.0f, 0.0f};
  c.fov_y_deg = 90.0f;
  // Looking down -z from +5: the view matrix is a translation by -5 along z.
  const Mat4 view = view_matrix(c);
  const Mat4 expected_view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1};
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(view[i], expected_view[i], 1e-6f) << i;
  // fov 90 deg, aspect 2, near 1, far 9: f = 1, x scaled by 1/2, z maps [-1, -9] to [-1, 1].
  const Mat4 proj = projection_matrix(c, 2.0f, 1.0f, 9.0f);
  const Mat4 expected_proj = {0.5f,          0, 0, 0, 0, 1, 0, 0, 0, 0, -10.0f / 8.0f, -1, 0, 0,
                              -18.0f / 8.0f, 0};
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(proj[i], expected_proj[i], 1e-6f) << i;

  const auto origin = to_ndc(c, 2.0f, 1.0f, 9.0f, {0.0f, 0.0f, 0.0f});
  EXPECT_NEAR(origin[0], 0.0f, 1e-6f);
  EXPECT_NEAR(origin[1], 0.0f, 1e-6f);
  const auto right_up = to_ndc(c, 2.0f, 1.0f, 9.0f, {1.0f, 1.0f, 0.0f});
  EXPECT_NEAR(right_up[0], 0.5f * 1.0f / 5.0f, 1e-6f);  // x / (aspect * depth)
  EXPECT_NEAR(right_up[1], 1.0f / 5.0f, 1e-6f);
  EXPECT_NEAR(to_ndc(c, 2.0f, 1.0f, 9.0f, {0.0f, 0.0f, 4.0f})[2], -1.0f,
              1e-5f);  // on the near plane
  EXPECT_NEAR(to_ndc(c, 2.0f, 1.0f, 9.0f, {0.0f, 0.0f, -4.0f})[2], 1.0f,
              1e-5f);  // on the far plane
}

TEST(RenderCamera, UpParallelToViewDirectionStillGivesAnOrthonormalView) {
  Camera c;
  c.eye = {0.0f, 0.0f, 4.0f};
  c.target = {0.0f, 0.0f, 0.0f};
  c.up = {0.0f, 0.0f, 1.0f};
  const Mat4 v = view_matrix(c);
  for (const float x : v) EXPECT_TRUE(std::isfinite(x));
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      float d = 0.0f;
      for (int k = 0; k < 3; ++k) d += v[k * 4 + a] * v[k * 4 + b];  // rows a and b
      EXPECT_NEAR(d, a == b ? 1.0f : 0.0f, 1e-5f);
    }
  }
}

TEST(RenderCamera, InvalidArgumentsThrow) {
  const std::array<Point3, 2> bounds = {Point3{0, 0, 0}, Point3{1, 1, 1}};
  EXPECT_THROW(fit_camera(bounds, 0.0f), std::invalid_argument);
  EXPECT_THROW(fit_camera(bounds, 1.0f, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(fit_camera(bounds, 1.0f, {0, 1, 0}, {0, 0, 1}, 175.0f), std::invalid_argument);
  Camera c;
  c.eye = c.target;
  EXPECT_THROW(view_matrix(c), std::invalid_argument);
  EXPECT_THROW(projection_matrix(Camera{}, 1.0f, 0.0f, 1.0f), std::invalid_argument);
  EXPECT_THROW(projection_matrix(Camera{}, 1.0f, 2.0f, 1.0f), std::invalid_argument);
}

TEST(RenderCamera, SceneBoundsCoverAllItemsAndSkipNonFinitePoints) {
  Scene scene;
  EXPECT_EQ(scene_bounds(scene)[0], (Point3{-0.5f, -0.5f, -0.5f}));
  EXPECT_EQ(scene_bounds(scene)[1], (Point3{0.5f, 0.5f, 0.5f}));

  const std::vector<float> positions = {0, 0, 0, 1, 2, 3, NAN, 100, 100};
  SurfaceItem surface;
  surface.positions = positions;
  scene.surfaces.push_back(surface);
  scene.polylines.push_back({{{-4.0f, 0.0f, 0.0f}, {0.0f, 5.0f, 0.0f}}});
  scene.points.push_back({{{0.0f, 0.0f, -6.0f}}});
  const auto b = scene_bounds(scene);
  EXPECT_EQ(b[0], (Point3{-4.0f, 0.0f, -6.0f}));
  EXPECT_EQ(b[1], (Point3{1.0f, 5.0f, 3.0f}));
}

}  // namespace
}  // namespace sutura::render
