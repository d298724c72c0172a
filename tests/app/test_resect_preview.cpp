// The Resect tool's cuts: a click on the wall gives a plane across the vessel, centred on the
// lumen, perpendicular to its axis; two give the band the resect op removes.
#include <gtest/gtest.h>

#include <cmath>

#include "sutura/app/resect_preview.hpp"
#include "sutura/engine/generators.hpp"

using namespace sutura;
using engine::Vec3;

namespace {

engine::SurfaceMesh tube() {
  engine::TubeParams p;
  p.radius = 4.0;
  p.length = 30.0;
  p.segments_around = 32;
  p.segments_along = 30;
  return engine::make_tube(p);
}

}  // namespace

TEST(ResectPreview, AClickOnTheWallCutsAcrossTheVesselThroughItsCentre) {
  const engine::SurfaceMesh m = tube();
  const engine::CentrelineTree tree = engine::extract_centreline(m);
  const double angle = 0.3;
  const app::SectionCut cut = app::cut_at(m, tree, Vec3(4.0 * std::sin(angle), 4.0 * std::cos(angle), 12.3));
  EXPECT_TRUE(cut.closed);
  EXPECT_NEAR(std::abs(cut.plane.normal.normalized().z()), 1.0, 1e-3);
  EXPECT_NEAR(cut.plane.origin.x(), 0.0, 0.05);
  EXPECT_NEAR(cut.plane.origin.y(), 0.0, 0.05);
  EXPECT_NEAR(cut.plane.origin.z(), 12.3, 1.0);  // a centreline point, about an edge apart
  EXPECT_NEAR(cut.diameter, 8.0, 0.1);
  EXPECT_NEAR(cut.wall_distance, 4.0, 0.05);
}

TEST(ResectPreview, TwoCutsRemoveTheBandBetweenThem) {
  const engine::SurfaceMesh m = tube();
  const engine::CentrelineTree tree = engine::extract_centreline(m);
  const app::ResectPreview p = app::preview_resection(m, tree, {Vec3(4, 0, 10), Vec3(0, -4, 20)}, 0.0);
  ASSERT_TRUE(p.error.empty()) << p.error;
  ASSERT_EQ(p.planes.size(), 2u);
  EXPECT_NEAR(p.reach, app::ResectPreview::kAutoReach * std::max(p.cuts[0].wall_distance, p.cuts[1].wall_distance),
              1e-12);
  ASSERT_EQ(p.loops.size(), 2u);
  const double dz = std::abs(p.planes[1].origin.z() - p.planes[0].origin.z());
  // The wall between the planes: a 32-gon prism 8 mm across.
  const double perimeter = 32 * 2.0 * 4.0 * std::sin(M_PI / 32);
  EXPECT_NEAR(p.removed_area, perimeter * dz, 0.02 * perimeter * dz);
  EXPECT_GT(p.removed_faces, 0u);
  EXPECT_FALSE(p.removed.empty());
  for (const Vec3& c : p.removed) {
    EXPECT_GT(c.z(), std::min(p.planes[0].origin.z(), p.planes[1].origin.z()) - 1.0);
    EXPECT_LT(c.z(), std::max(p.planes[0].origin.z(), p.planes[1].origin.z()) + 1.0);
  }
  // One click so far: the cut, no resection yet.
  const app::ResectPreview one = app::preview_resection(m, tree, {Vec3(4, 0, 10)}, 0.0);
  EXPECT_EQ(one.planes.size(), 1u);
  EXPECT_TRUE(one.loops.empty());
  EXPECT_TRUE(one.error.empty());
}

TEST(ResectPreview, CutsThatCannotBeMadeAreExplained) {
  const engine::SurfaceMesh m = tube();
  const engine::CentrelineTree tree = engine::extract_centreline(m);
  // Both clicks on the same section.
  const app::ResectPreview same = app::preview_resection(m, tree, {Vec3(4, 0, 10), Vec3(-4, 0, 10)}, 0.0);
  EXPECT_FALSE(same.error.empty());
  // A reach shorter than the lumen: the cut does not go all the way round.
  const app::ResectPreview short_reach = app::preview_resection(m, tree, {Vec3(4, 0, 10), Vec3(4, 0, 20)}, 2.0);
  EXPECT_FALSE(short_reach.error.empty());
  EXPECT_TRUE(short_reach.loops.empty());
}
