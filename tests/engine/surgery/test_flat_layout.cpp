// unfold_rest: a region's rest shape laid out flat (the cutting pattern of a patch).
#include "sutura/engine/surgery/flat_layout.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

std::vector<FaceId> all_faces(const SurfaceMesh& m) {
  std::vector<FaceId> f;
  for (std::size_t i = 0; i < m.num_faces(); ++i) f.emplace_back(i);
  return f;
}

std::vector<Vec2> outline_points(const FlatLayout& l) {
  std::vector<Vec2> p;
  for (VertexId v : l.outline) p.push_back(l.position[v.index()]);
  return p;
}

// A flat patch turned and moved in space, its rest congruent with it: the layout is the patch
// itself, up to a rigid motion of the plane.
TEST(FlatLayout, AFlatPatchUnfoldsToItselfWithoutGaps) {
  PatchParams pp;
  pp.length = 24.0;
  pp.width = 6.0;
  pp.target_edge_length = 0.8;
  SurfaceMesh patch = make_patch(pp);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Vec3> x = patch.positions();
  for (Vec3& p : x) p = R * p + Vec3(5, -2, 11);
  patch.set_positions(x);
  const RestState rest = rest_from_state(patch, state_from_mesh(patch));

  const FlatLayout l = unfold_rest(patch, rest, all_faces(patch));
  EXPECT_LT(l.max_gap_mm, 1e-12);
  EXPECT_NEAR(l.rest_area_mm2, patch.total_area(), 1e-9 * patch.total_area());
  const std::vector<Vec2> outline = outline_points(l);
  // Counter-clockwise, and the polygon's area and length are the rest shape's.
  EXPECT_NEAR(polygon_area(outline), l.rest_area_mm2, 1e-9 * l.rest_area_mm2);
  EXPECT_NEAR(polygon_perimeter(outline), l.rest_perimeter_mm, 1e-9 * l.rest_perimeter_mm);
  ASSERT_EQ(patch.boundary_loops().size(), 1u);
  EXPECT_EQ(l.outline.size(), patch.boundary_loops()[0].size());
  EXPECT_EQ(l.outline.front(), patch.boundary_loops()[0].front());
  // Every pairwise distance of the layout is the one in space (a rigid motion).
  for (std::size_t i = 0; i < x.size(); i += 7)
    for (std::size_t j = i + 1; j < x.size(); j += 5)
      EXPECT_NEAR((l.position[i] - l.position[j]).norm(), (x[i] - x[j]).norm(), 1e-10);
  // An ellipse of axes 24 x 6: its perimeter is near Ramanujan's (the polygon is inscribed).
  const double a = 12.0, b = 3.0, h = (a - b) * (a - b) / ((a + b) * (a + b));
  const double ellipse = std::numbers::pi * (a + b) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h)));
  EXPECT_LT(l.rest_perimeter_mm, ellipse);
  EXPECT_GT(l.rest_perimeter_mm, 0.99 * ellipse);
}

// The rest shape, not the current one, is laid out: a patch bent onto a cylinder whose rest
// is still the flat cut unfolds to the flat cut.
TEST(FlatLayout, TheRestShapeIsLaidOutNotTheCurrentOne) {
  PatchParams pp;
  pp.length = 16.0;
  pp.width = 6.0;
  SurfaceMesh patch = make_patch(pp);
  const RestState rest = rest_from_state(patch, state_from_mesh(patch));
  const double flat_area = patch.total_area();
  std::vector<Vec3> x = patch.positions();
  for (Vec3& p : x) p = Vec3(p.x(), 4.0 * std::sin(p.y() / 4.0), 4.0 * std::cos(p.y() / 4.0));
  patch.set_positions(x);
  const FlatLayout l = unfold_rest(patch, rest, all_faces(patch));
  EXPECT_LT(l.max_gap_mm, 1e-12);
  EXPECT_NEAR(polygon_area(outline_points(l)), flat_area, 1e-9 * flat_area);
}

// A cap of a sphere cannot be cut flat: the layout says by how much.
TEST(FlatLayout, ACurvedRestShapeReportsItsGap) {
  PatchParams pp;
  pp.length = 10.0;
  pp.width = 10.0;
  pp.target_edge_length = 0.7;
  SurfaceMesh cap = make_patch(pp);
  std::vector<Vec3> x = cap.positions();
  const double R = 8.0;
  for (Vec3& p : x) {
    const double r = std::hypot(p.x(), p.y());
    const double t = r / R;  // arc length r on the sphere
    const double s = r > 0 ? std::sin(t) * R / r : 1.0;
    p = Vec3(p.x() * s, p.y() * s, R * std::cos(t));
  }
  cap.set_positions(x);
  const RestState rest = rest_from_state(cap, state_from_mesh(cap));
  const FlatLayout l = unfold_rest(cap, rest, all_faces(cap));
  // Flat, the gap is round-off (above: below 1e-12). On the sphere the layout gapes, but by
  // less than the rim's shortfall against a flat disk of the same radius, 2 pi (r - R sin(r/R)),
  // which the whole unfolding would have to absorb at a single seam.
  const double r = 5.0, shortfall = 2 * std::numbers::pi * (r - R * std::sin(r / R));
  EXPECT_GT(l.max_gap_mm, 0.01);
  EXPECT_LT(l.max_gap_mm, shortfall);
}

TEST(FlatLayout, PartOfAMeshUnfoldsItsRegionOnly) {
  TubeParams tp;
  tp.radius = 4.0;
  tp.length = 10.0;
  tp.segments_around = 24;
  tp.segments_along = 10;
  const SurfaceMesh tube = make_tube(tp);
  const RestState rest = rest_from_state(tube, state_from_mesh(tube));
  // The faces on the +x side between z = 2 and 8: a developable disk of the tube.
  std::vector<FaceId> region;
  for (std::size_t f = 0; f < tube.num_faces(); ++f) {
    const Vec3 c = tube.face_centroid(FaceId(f));
    if (c.x() > 2.0 && c.z() > 2.0 && c.z() < 8.0) region.emplace_back(f);
  }
  ASSERT_FALSE(region.empty());
  const FlatLayout l = unfold_rest(tube, rest, region);
  double area = 0.0;
  for (FaceId f : region) area += tube.face_area(f);
  EXPECT_NEAR(l.rest_area_mm2, area, 1e-9 * area);
  EXPECT_NEAR(polygon_area(outline_points(l)), area, 1e-9 * area);
  EXPECT_LT(l.max_gap_mm, 1e-12);  // a triangulated cylinder strip is a flat strip folded
  std::size_t laid = 0;
  for (const Vec2& p : l.position) laid += std::isfinite(p.x()) ? 1 : 0;
  EXPECT_LT(laid, tube.num_vertices());
}

TEST(FlatLayout, RefusesRegionsThatAreNotOneDisk) {
  TubeParams tp;
  tp.segments_around = 12;
  tp.segments_along = 6;
  const SurfaceMesh tube = make_tube(tp);
  const RestState rest = rest_from_state(tube, state_from_mesh(tube));
  auto message = [&](const std::vector<FaceId>& region) {
    try {
      (void)unfold_rest(tube, rest, region);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({}).find("no faces"), std::string::npos);
  EXPECT_NE(message({FaceId(std::size_t{100000})}).find("out of range"), std::string::npos);
  // The whole tube: two boundary loops.
  EXPECT_NE(message(all_faces(tube)).find("not one loop"), std::string::npos);
  // Two faces far apart.
  EXPECT_NE(message({FaceId(0), FaceId(tube.num_faces() - 1)}).find("not edge-connected"),
            std::string::npos);
  RestState flat = rest;
  flat.elements[0].X[2] = flat.elements[0].X[1];
  try {
    (void)unfold_rest(tube, flat, {FaceId(0)});
    ADD_FAILURE() << "a degenerate rest triangle was laid out";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos);
  }
}

}  // namespace
}  // namespace sutura::engine
