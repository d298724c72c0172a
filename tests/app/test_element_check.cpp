// The check before a run: rest triangles too thin to relax refuse it, thin ones warn, and
// both are located for the view's markers.
#include <gtest/gtest.h>

#include <cmath>

#include "sutura/app/element_check.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/surgery/remesh.hpp"

using namespace sutura;

namespace {

// Makes face f's rest triangle isosceles with apex angle `deg` (its smallest angle).
void thin(app::SceneObject& o, int f, double deg) {
  auto& X = o.sim.rest.elements[std::size_t(f)].X;
  const engine::Vec3 base = X[1] - X[0];
  const engine::Vec3 n = base.cross(X[2] - X[0]).normalized();
  const engine::Vec3 across = n.cross(base).normalized();
  const double half = std::tan(0.5 * deg * M_PI / 180.0);
  // Apex beyond the base's midpoint, so the apex angle is the smallest.
  X[2] = X[0] + 0.5 * base + across * (0.5 * base.norm() / half);
}

engine::Vec3 centroid(const app::SceneObject& o, int f) {
  const auto v = o.mesh.face_vertices(engine::FaceId(f));
  return (o.mesh.position(v[0]) + o.mesh.position(v[1]) + o.mesh.position(v[2])) / 3.0;
}

}  // namespace

TEST(ElementCheck, ThinRestTrianglesRefuseOrWarn) {
  app::Workspace w;
  w.add("strip", engine::make_strip({}));
  w.add("other", engine::make_strip({}));
  EXPECT_FALSE(app::check_elements(w).refusal());
  EXPECT_FALSE(app::check_elements(w).warning());

  app::SceneObject& o = *w.edit("strip");
  thin(o, 7, 5.0);   // warned
  thin(o, 40, 2.0);  // refused
  thin(o, 12, 0.5);  // refused, the smallest
  const auto& X = o.sim.rest.elements[12].X;
  ASSERT_NEAR(engine::smallest_angle_deg(X[0], X[1], X[2]), 0.5, 1e-9);

  const app::ElementCheck c = app::check_elements(w);
  ASSERT_EQ(c.refused.size(), 1u);
  EXPECT_EQ(c.refused[0].object, "strip");
  EXPECT_EQ(c.refused[0].count, 2u);
  EXPECT_NEAR(c.refused[0].smallest_deg, 0.5, 1e-9);
  ASSERT_EQ(c.refused[0].where.size(), 2u);
  EXPECT_EQ(c.refused[0].where[0], centroid(o, 12));  // the smallest first
  EXPECT_EQ(c.refused[0].where[1], centroid(o, 40));
  ASSERT_EQ(c.warned.size(), 1u);
  EXPECT_EQ(c.warned[0].count, 1u);
  EXPECT_EQ(c.warned[0].where[0], centroid(o, 7));
  ASSERT_TRUE(c.refusal());
  EXPECT_NE(c.refusal()->find("2 rest triangles of 'strip' (smallest angle 0.50 degrees"), std::string::npos)
      << *c.refusal();
  ASSERT_TRUE(c.warning());
  EXPECT_NE(c.warning()->find("1 rest triangle of 'strip' (smallest angle 5.00 degrees"), std::string::npos)
      << *c.warning();
}

TEST(ElementCheck, MarkersAreBoundedAndKeepTheSmallest) {
  app::Workspace w;
  engine::StripParams p;
  p.segments_length = 60;
  p.segments_width = 10;
  w.add("strip", engine::make_strip(p));
  app::SceneObject& o = *w.edit("strip");
  const int faces = int(o.mesh.num_faces());
  for (int f = 0; f < faces; ++f) thin(o, f, 2.0);
  thin(o, faces - 1, 1.0);
  const app::ElementCheck c = app::check_elements(w);
  ASSERT_EQ(c.refused.size(), 1u);
  EXPECT_EQ(c.refused[0].count, std::size_t(faces));
  EXPECT_EQ(c.refused[0].where.size(), app::ElementCheck::kMaxMarkers);
  EXPECT_EQ(c.refused[0].where[0], centroid(o, faces - 1));
  EXPECT_NEAR(c.refused[0].smallest_deg, 1.0, 1e-9);
}

// The shape shown (current positions), not the rest shape: a vertex moved towards its
// neighbour makes the smallest angle, and the rest angle of that face is reported beside it.
TEST(ElementCheck, SmallestAnglesAreOfTheCurrentShapeAndSayWhere) {
  app::Workspace w;
  w.add("strip", engine::make_strip({}));
  w.add("other", engine::make_strip({}));
  const double generated = engine::mesh_quality(w.objects()[0].mesh).min_angle_deg;
  app::SceneObject& o = *w.edit("strip");
  const auto v = o.mesh.face_vertices(engine::FaceId(9));
  // Squeeze face 9: its third corner onto its first edge's midpoint, less a little.
  const engine::Vec3 mid = 0.5 * (o.mesh.position(v[0]) + o.mesh.position(v[1]));
  o.mesh.set_position(v[2], mid + 0.05 * (o.mesh.position(v[2]) - mid));
  o.sim.state.x[std::size_t(v[2].index())] = o.mesh.position(v[2]);

  // That face's rest triangle gets its own angle, so the rest angle reported is of that face.
  const engine::FaceId worst = engine::mesh_quality(o.mesh).worst_face;
  thin(o, worst.index(), 15.0);

  const std::vector<app::SmallestAngle> a = app::smallest_angles(w);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].object, "strip");
  EXPECT_LT(a[0].degrees, 10.0);
  EXPECT_DOUBLE_EQ(a[0].degrees, engine::mesh_quality(o.mesh).min_angle_deg);
  EXPECT_EQ(a[0].where, centroid(o, worst.index()));
  EXPECT_NEAR(a[0].rest_degrees, 15.0, 1e-9);
  EXPECT_EQ(a[1].object, "other");
  EXPECT_DOUBLE_EQ(a[1].degrees, generated);
}
