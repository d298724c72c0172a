// The GUI camera: fitting matches the snapshot camera, and picking rays and projection
// are inverse to each other.
#include <gtest/gtest.h>

#include "sutura/ui/orbit_camera.hpp"

using namespace sutura;

namespace {

const std::array<render::Point3, 2> kBounds = {{{-4, -4, 0}, {4, 4, 30}}};

engine::Vec3 vec(const render::Point3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

TEST(OrbitCamera, FitMatchesTheSnapshotCamera) {
  ui::OrbitCamera cam;
  cam.fit(kBounds, 1.5f);
  const render::Camera want = render::fit_camera(kBounds, 1.5f);
  const render::Camera got = cam.camera();
  EXPECT_LT((vec(got.eye) - vec(want.eye)).norm(), 1e-3);
  EXPECT_LT((vec(got.target) - vec(want.target)).norm(), 1e-4);
}

TEST(OrbitCamera, RayThroughCentreLooksAtTarget) {
  ui::OrbitCamera cam;
  cam.fit(kBounds, 1.0f);
  const engine::Ray r = cam.ray_through(399.5f, 399.5f, 800, 800);
  const render::Camera c = cam.camera();
  const engine::Vec3 to_target = (vec(c.target) - vec(c.eye)).normalized();
  EXPECT_NEAR(r.direction.dot(to_target), 1.0, 1e-9);
  EXPECT_LT((r.origin - vec(c.eye)).norm(), 1e-4);
}

TEST(OrbitCamera, ProjectInvertsRayThrough) {
  ui::OrbitCamera cam;
  cam.fit(kBounds, 1.6f);
  cam.orbit(40, -25);
  cam.pan(10, 5, 900);
  cam.zoom(2);
  for (auto [x, y] : {std::pair{100.0f, 200.0f}, {700.0f, 50.0f}, {1300.0f, 880.0f}}) {
    const engine::Ray r = cam.ray_through(x, y, 1440, 900);
    std::array<float, 2> px{};
    ASSERT_TRUE(cam.project(r.origin + 37.0 * r.direction, 1440, 900, px));
    EXPECT_NEAR(px[0], x, 1e-2);
    EXPECT_NEAR(px[1], y, 1e-2);
  }
  std::array<float, 2> px{};
  EXPECT_FALSE(cam.project(vec(cam.camera().eye) - 5.0 * (vec(cam.camera().target) - vec(cam.camera().eye)), 100, 100, px));
}

TEST(OrbitCamera, StandardViewsLookFromWhereTheyAreNamed) {
  // Patient frame: +x left, +y posterior, +z superior. Each view: the direction the eye looks
  // along, and the world direction that shows to the right on screen.
  struct Case {
    ui::StandardView view;
    engine::Vec3 look, right;
  };
  const double c89 = std::cos(89.0 * M_PI / 180.0), s89 = std::sin(89.0 * M_PI / 180.0);
  for (const Case& k : {Case{ui::StandardView::Anterior, {0, 1, 0}, {1, 0, 0}},
                        Case{ui::StandardView::Posterior, {0, -1, 0}, {-1, 0, 0}},
                        Case{ui::StandardView::LeftLateral, {-1, 0, 0}, {0, 1, 0}},
                        Case{ui::StandardView::RightLateral, {1, 0, 0}, {0, -1, 0}},
                        Case{ui::StandardView::Superior, {0, c89, -s89}, {1, 0, 0}},
                        Case{ui::StandardView::Inferior, {0, c89, s89}, {1, 0, 0}}}) {
    ui::OrbitCamera cam;
    cam.fit(kBounds, 1.0f);
    cam.orbit(123, -45);  // wherever it looked before
    const render::Camera before = cam.camera();
    cam.look_from(k.view);
    const render::Camera c = cam.camera();
    const engine::Vec3 look = (vec(c.target) - vec(c.eye)).normalized();
    EXPECT_LT((look - k.look).norm(), 1e-6) << ui::to_string(k.view);
    EXPECT_LT((vec(c.target) - vec(before.target)).norm(), 1e-6);  // target and distance kept
    EXPECT_NEAR((vec(c.target) - vec(c.eye)).norm(), (vec(before.target) - vec(before.eye)).norm(), 1e-4);
    std::array<float, 2> centre{}, right{};
    ASSERT_TRUE(cam.project(vec(c.target), 800, 800, centre));
    ASSERT_TRUE(cam.project(vec(c.target) + k.right, 800, 800, right));
    EXPECT_GT(right[0] - centre[0], 1.0f) << ui::to_string(k.view);
    EXPECT_NEAR(right[1], centre[1], 1e-2) << ui::to_string(k.view);
  }
}

TEST(OrbitCamera, ZoomTowardsAPointKeepsItUnderThePointer) {
  ui::OrbitCamera cam;
  cam.fit(kBounds, 1.5f);
  cam.orbit(30, 10);
  const engine::Ray r = cam.ray_through(200.0f, 650.0f, 1200, 800);
  const engine::Vec3 p = r.origin + 40.0 * r.direction;
  const double d0 = (vec(cam.camera().target) - vec(cam.camera().eye)).norm();
  for (float steps : {3.0f, -5.0f, 1.5f}) {
    cam.zoom_towards(p, steps);
    std::array<float, 2> px{};
    ASSERT_TRUE(cam.project(p, 1200, 800, px));
    EXPECT_NEAR(px[0], 200.0f, 0.02f) << steps;
    EXPECT_NEAR(px[1], 650.0f, 0.02f) << steps;
  }
  // The distance changed as zoom() changes it: 0.9^(3 - 5 + 1.5).
  const double d1 = (vec(cam.camera().target) - vec(cam.camera().eye)).norm();
  EXPECT_NEAR(d1 / d0, std::pow(0.9, -0.5), 1e-4);
}
