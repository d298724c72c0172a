// Picking in the view: the nearest object under the ray, and the boundary vertex a suture or
// fix click snaps to.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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

// With Cut open, what is cut away is not picked: a ray from the eye through a tube whose near
// half is cut away hits the far wall; a ray that stays on the cut side hits nothing.
TEST(ScenePicker, APlaneCutsAwayThePartOfTheRayOnItsNormalsSide) {
  engine::TubeParams t;
  const engine::SurfaceMesh tube = engine::make_tube(t);  // axis z, radius t.radius
  ui::ScenePicker picker;
  picker.rebuild({&tube});
  const engine::Ray ray{engine::Vec3(30, 0, 10), engine::Vec3(-1, 0, 0)};
  const auto whole = ui::uncut_part(ray, std::nullopt);
  EXPECT_EQ(whole[0], 0.0);
  EXPECT_EQ(whole[1], std::numeric_limits<double>::infinity());
  const auto near_wall = picker.pick(ray, 0.0, whole[0], whole[1]);
  ASSERT_TRUE(near_wall);
  EXPECT_NEAR(near_wall->hit.point.x(), t.radius, 0.05);

  const render::ClipPlane facing_the_eye{{0.0f, 0.0f, 10.0f}, {1.0f, 0.0f, 0.0f}};
  const auto cut = ui::uncut_part(ray, facing_the_eye);
  EXPECT_DOUBLE_EQ(cut[0], 30.0);  // where the ray crosses the plane
  const auto far_wall = picker.pick(ray, 0.0, cut[0], cut[1]);
  ASSERT_TRUE(far_wall);
  EXPECT_NEAR(far_wall->hit.point.x(), -t.radius, 0.05);

  // An eye on the kept side looking into the cut side: only the part before the plane is left.
  const engine::Ray inward{engine::Vec3(-30, 0, 10), engine::Vec3(1, 0, 0)};
  const auto before_plane = ui::uncut_part(inward, facing_the_eye);
  EXPECT_EQ(before_plane[0], 0.0);
  EXPECT_DOUBLE_EQ(before_plane[1], 30.0);
  const auto hit = picker.pick(inward, 0.0, before_plane[0], before_plane[1]);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->hit.point.x(), -t.radius, 0.05);
  // Away from the plane on the cut side: nothing left, nothing picked.
  const auto none = ui::uncut_part({engine::Vec3(30, 0, 10), engine::Vec3(1, 0, 0)}, facing_the_eye);
  EXPECT_GT(none[0], none[1]);
  EXPECT_FALSE(picker.pick({engine::Vec3(30, 0, 10), engine::Vec3(1, 0, 0)}, 0.0, none[0], none[1]));
}

TEST(ScenePicker, AClickNearACornerPicksIt) {
  const engine::SurfaceMesh m =
      engine::load_mesh(std::string(SUTURA_SOURCE_DIR) + "/tests/gui/two_strips.obj");
  ui::ScenePicker picker;
  picker.rebuild({&m});
  // 0.45 mm from the boundary vertex (18, -4), 1.26 mm from the corner (18, -5), seen from 10 mm.
  const engine::Ray ray{engine::Vec3(17.6, -3.8, 10), engine::Vec3(0, 0, -1)};
  const auto plain = picker.pick(ray);
  ASSERT_TRUE(plain);
  EXPECT_EQ(m.position(plain->boundary_vertex), engine::Vec3(18, -4, 0));
  // A snap angle reaching 1.5 mm at 10 mm: the corner wins.
  const auto snapped = picker.pick(ray, std::atan(0.15));
  ASSERT_TRUE(snapped);
  EXPECT_EQ(m.position(snapped->boundary_vertex), engine::Vec3(18, -5, 0));
  EXPECT_EQ(snapped->boundary_loop, plain->boundary_loop);
  // A reach of 1.0 mm does not get there: the nearest boundary vertex again.
  EXPECT_EQ(m.position(picker.pick(ray, std::atan(0.10))->boundary_vertex), engine::Vec3(18, -4, 0));
  // The middle of a straight edge is no corner: (18, 0) is taken only when it is the nearest.
  const auto middle = picker.pick({engine::Vec3(17.6, 0.3, 10), engine::Vec3(0, 0, -1)}, std::atan(0.3));
  ASSERT_TRUE(middle);
  EXPECT_EQ(m.position(middle->boundary_vertex), engine::Vec3(18, 0, 0));
}
