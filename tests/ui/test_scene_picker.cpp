// Picking in the view: the nearest object under the ray, and the boundary vertex a suture or
// fix click snaps to.
#include <gtest/gtest.h>

#include "../../ui/src/scene_picker.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/mesh_io.hpp"

using namespace sutura;

TEST(ScenePicker, SnapsToTheNearestBoundaryVertexOfTheHitObject) {
  const engine::SurfaceMesh strips =
      engine::load_mesh(std::string(SUTURA_SOURCE_DIR) + "/tests/gui/two_strips.obj");
  ui::ScenePicker picker;
  picker.rebuild({&strips});
  for (auto [x, y, want_x, want_y] : {std::array<double, 4>{17.7, -4.6, 18, -5}, {17.7, 4.6, 18, 5},
                                      {22.3, 4.6, 22, 5}, {22.3, -4.6, 22, -5}}) {
    // An oblique ray through (x, y, 0).
    const auto pick = picker.pick({engine::Vec3(x - 1.0, y - 2.0, 10), engine::Vec3(0.1, 0.2, -1)});
    ASSERT_TRUE(pick);
    ASSERT_GE(pick->boundary_loop, 0);
    const engine::Vec3& v = strips.position(pick->boundary_vertex);
    EXPECT_NEAR(v.x(), want_x, 1e-12) << x << " " << y;
    EXPECT_NEAR(v.y(), want_y, 1e-12) << x << " " << y;
  }
  // Far from the boundary (more than 3 edge lengths): no boundary vertex.
  const auto inner = picker.pick({engine::Vec3(9, 0, 10), engine::Vec3(0, 0, -1)});
  ASSERT_TRUE(inner);
  EXPECT_EQ(inner->boundary_loop, -1);
  EXPECT_FALSE(picker.pick({engine::Vec3(20, 0, 10), engine::Vec3(0, 0, -1)}));  // the gap
}

TEST(ScenePicker, NearestOfTwoObjectsWins) {
  engine::TubeParams t;
  const engine::SurfaceMesh a = engine::make_tube(t);
  engine::SurfaceMesh b = engine::make_tube(t);
  std::vector<engine::Vec3> moved = b.positions();
  for (auto& p : moved) p.x() += 20.0;
  b.set_positions(moved);
  ui::ScenePicker picker;
  picker.rebuild({&a, &b});
  const auto from_right = picker.pick({engine::Vec3(60, 0, 10), engine::Vec3(-1, 0, 0)});
  ASSERT_TRUE(from_right);
  EXPECT_EQ(from_right->object, 1u);
  EXPECT_NEAR(from_right->hit.point.x(), 20.0 + t.radius, 0.05);
  const auto from_left = picker.pick({engine::Vec3(-60, 0, 10), engine::Vec3(1, 0, 0)});
  ASSERT_TRUE(from_left);
  EXPECT_EQ(from_left->object, 0u);
}
