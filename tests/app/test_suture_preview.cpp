// The suture tool's reading of clicks: each side's two ends in either order, the shorter arc
// between them (or the long way round), side B never on side A's arc, recorded in the
// boundary direction; the same point twice on a cut (lip round to lip, a flap) or on an open
// end (its loop); (a click near a boundary corner picking the corner: test_scene_picker.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "sutura/app/op_builders.hpp"
#include "sutura/app/suture_preview.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/mesh_io.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"
#include "sutura/engine/surgery/incise.hpp"

using namespace sutura;
using engine::Vec3;

namespace {

engine::SurfaceMesh two_strips() {
  return engine::load_mesh(std::string(SUTURA_SOURCE_DIR) + "/tests/gui/two_strips.obj");
}

// As the join op resolves a recorded side.
engine::BoundaryChain chain(const engine::SurfaceMesh& m, const app::ChainEnds& side) {
  engine::ChainSpec s;
  s.from = side.from;
  s.to = side.to;
  s.via = side.via;
  s.loop = side.loop();
  return engine::find_boundary_chain(m, s);
}

std::vector<Vec3> ends_of(const std::vector<app::ChainEnds>& sides) {
  std::vector<Vec3> out;
  for (const auto& s : sides) {
    out.push_back(s.from);
    out.push_back(s.to);
  }
  return out;
}

}  // namespace

TEST(SuturePreview, BothSidesClickedTheSameWayAreOrientedForTheJoin) {
  const engine::SurfaceMesh m = two_strips();
  // Facing edges of the strips (x = 18 and x = 22), both clicked from y = -5 to y = 5. The left
  // strip's boundary runs up its right edge, the right strip's down its left edge.
  const std::vector<Vec3> clicks = {{18, -5, 0}, {18, 5, 0}, {22, -5, 0}, {22, 5, 0}};
  const auto oriented = ends_of(app::suture_sides(m, clicks));
  ASSERT_EQ(oriented.size(), 4u);
  EXPECT_EQ(oriented[0], clicks[0]);
  EXPECT_EQ(oriented[1], clicks[1]);
  EXPECT_EQ(oriented[2], clicks[3]);  // side B swapped: as clicked it is the long way round
  EXPECT_EQ(oriented[3], clicks[2]);
  const app::SuturePreview p = app::preview_suture(m, clicks);
  ASSERT_EQ(p.chains.size(), 2u);
  EXPECT_EQ(p.chains[0].size(), 11u);
  EXPECT_EQ(p.chains[1].size(), 11u);
  // y = -5 meets y = -5: A's first end with B's last.
  ASSERT_EQ(p.meeting_ends.size(), 2u);
  EXPECT_EQ(p.meeting_ends[0][0], Vec3(18, -5, 0));
  EXPECT_EQ(p.meeting_ends[0][1], Vec3(22, -5, 0));
  EXPECT_EQ(p.meeting_ends[1][0], Vec3(18, 5, 0));
  EXPECT_EQ(p.meeting_ends[1][1], Vec3(22, 5, 0));
  // Clicking side A the other way gives the same join.
  const auto reversed = ends_of(app::suture_sides(m, {clicks[1], clicks[0], clicks[2], clicks[3]}));
  EXPECT_EQ(reversed, oriented);
  for (const auto& side : app::suture_sides(m, clicks)) EXPECT_FALSE(side.via);  // the ends suffice
}

TEST(SuturePreview, TheLongWayRoundIsTakenOnlyWhenAskedFor) {
  const engine::SurfaceMesh m = two_strips();
  const std::vector<Vec3> a = {{18, -5, 0}, {18, 5, 0}};
  const auto shorter = app::suture_sides(m, a);
  ASSERT_EQ(shorter.size(), 1u);
  EXPECT_NEAR(engine::chain_length(m, chain(m, shorter[0])), 10.0, 1e-12);
  const auto longer = app::suture_sides(m, a, {true, false});
  ASSERT_EQ(longer.size(), 1u);
  EXPECT_NEAR(engine::chain_length(m, chain(m, longer[0])), 46.0, 1e-12);
  // One click so far: no side yet.
  EXPECT_TRUE(app::suture_sides(m, {a[0]}).empty());
}

TEST(SuturePreview, ClickingBothLipsFromTheSameEndGivesTheTwoLips) {
  engine::StripParams sp;
  const engine::IncisionResult cut = engine::incise(engine::make_strip(sp), {{10, 0.3, 0}, {30, 0.3, 0}});
  const engine::SurfaceMesh& m = cut.mesh;
  const Vec3 first = m.position(cut.left.front()), last = m.position(cut.left.back());
  // Both sides clicked at the same two ends (the slit's tips), in the same order.
  const auto sides = app::suture_sides(m, {first, last, first, last});
  ASSERT_EQ(sides.size(), 2u);
  const engine::BoundaryChain a = chain(m, sides[0]);
  const engine::BoundaryChain b = chain(m, sides[1]);
  const auto as_set = [](const std::vector<engine::VertexId>& v) {
    return std::set<engine::VertexId>(v.begin(), v.end());
  };
  const std::set<engine::VertexId> left = as_set(cut.left), right = as_set(cut.right);
  EXPECT_NE(as_set(a.vertices), as_set(b.vertices));
  EXPECT_TRUE((as_set(a.vertices) == left && as_set(b.vertices) == right) ||
              (as_set(a.vertices) == right && as_set(b.vertices) == left));
  const app::SuturePreview p = app::preview_suture(m, {first, last, first, last});
  ASSERT_EQ(p.meeting_ends.size(), 2u);
  EXPECT_EQ(p.meeting_ends[0][0], p.meeting_ends[0][1]);  // a slit: its ends are shared
}

TEST(SuturePreview, TheSameVertexTwiceIsItsWholeLoop) {
  engine::TubeParams tp;
  tp.radius = 4.0;
  tp.length = 20.0;
  const engine::SurfaceMesh m = engine::make_tube(tp);
  const Vec3 bottom = m.position(m.boundary_loops()[0][3]);
  const Vec3 top = m.position(m.boundary_loops()[1][5]);
  const std::vector<Vec3> clicks = {bottom, bottom, top, top};
  const auto sides = app::suture_sides(m, clicks);
  ASSERT_EQ(sides.size(), 2u);
  EXPECT_TRUE(sides[0].loop() && sides[1].loop());
  EXPECT_EQ(ends_of(sides), clicks);  // loops are not reordered
  const app::SuturePreview p = app::preview_suture(m, clicks);
  ASSERT_EQ(p.chains.size(), 2u);
  EXPECT_EQ(p.chains[0].size(), m.boundary_loops()[0].size());
  EXPECT_EQ(p.chains[1].size(), m.boundary_loops()[1].size());
  EXPECT_EQ(p.chains[0].front(), bottom);
  EXPECT_EQ(p.chains[1].front(), top);
  EXPECT_NEAR(p.lengths[0], 2.0 * 32 * 4.0 * std::sin(M_PI / 32), 1e-9);  // closing edge included
  // Two loops meet at their first vertices.
  ASSERT_EQ(p.meeting_ends.size(), 1u);
  EXPECT_EQ(p.meeting_ends[0][0], bottom);
  EXPECT_EQ(p.meeting_ends[0][1], top);
  // Recorded as loops.
  const nlohmann::json op = app::join_op("a", {bottom, bottom, std::nullopt}, {top, top, std::nullopt}, false);
  EXPECT_EQ(op["chains"][0], nlohmann::json({{"loop", {bottom.x(), bottom.y(), bottom.z()}}}));
  EXPECT_EQ(op["chains"][1], nlohmann::json({{"loop", {top.x(), top.y(), top.z()}}}));
  const nlohmann::json open = app::join_op("a", {bottom, top, std::nullopt}, {top, bottom, std::nullopt}, false);
  EXPECT_TRUE(open["chains"][0].contains("from"));
}

// A cut from the strip's edge that turns a corner: the corner point has a copy on each lip.
// Clicked twice, lip to lip, it names an arc from one copy to the other; clicked twice for each side, the
// short arc (round the cut's inner tip, the "aortotomy") and the long one (down one lip,
// round the strip and up the other, the "flap"), each recorded with a `via` that makes the
// join resolve exactly that arc.
TEST(SuturePreview, TheSamePointTwiceOnACutGoesFromLipToLip) {
  engine::StripParams sp;
  const engine::IncisionResult cut =
      engine::incise(engine::make_strip(sp), {{20.3, -5, 0}, {20.3, 0.3, 0}, {30.3, 0.3, 0}});
  ASSERT_TRUE(cut.starts_on_boundary);
  const engine::SurfaceMesh& m = cut.mesh;
  const auto nearest = [&](const std::vector<engine::VertexId>& lip) {
    return *std::min_element(lip.begin(), lip.end(), [&](auto u, auto v) {
      return (m.position(u) - Vec3(20.3, 0.3, 0)).norm() < (m.position(v) - Vec3(20.3, 0.3, 0)).norm();
    });
  };
  const engine::VertexId left = nearest(cut.left), right = nearest(cut.right);
  ASSERT_NE(left, right);
  ASSERT_EQ(m.position(left), m.position(right));  // the corner's two copies
  const Vec3 corner = m.position(left);

  // Without lip_to_lip the same point twice is the whole loop there.
  const auto loops = app::suture_sides(m, {corner, corner});
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_TRUE(loops[0].loop());

  const auto sides = app::suture_sides(m, {corner, corner, corner, corner}, {false, false}, true);
  ASSERT_EQ(sides.size(), 2u);
  for (const auto& side : sides) {
    EXPECT_FALSE(side.loop());
    EXPECT_EQ(side.from, corner);
    EXPECT_EQ(side.to, corner);
    ASSERT_TRUE(side.via);
  }
  const engine::BoundaryChain a = chain(m, sides[0]), b = chain(m, sides[1]);
  const double tip = engine::chain_length(m, a), flap = engine::chain_length(m, b);
  // A round the cut's inner tip (about 2 x 10 mm of lip), B down both lips and round the
  // strip's four corners (about 2 x 5.3 + 100 mm): the band remesh moves the corner a little.
  const auto passes = [&](const engine::BoundaryChain& c, const Vec3& p) {
    for (auto v : c.vertices)
      if ((m.position(v) - p).norm() < 1e-9) return true;
    return false;
  };
  EXPECT_TRUE(passes(a, {30.3, 0.3, 0}));
  EXPECT_FALSE(passes(a, {0, -5, 0}));
  for (const Vec3& strip_corner : {Vec3(0, -5, 0), Vec3(40, -5, 0), Vec3(40, 5, 0), Vec3(0, 5, 0)})
    EXPECT_TRUE(passes(b, strip_corner));
  EXPECT_NEAR(tip, 20.0, 1.0);
  EXPECT_NEAR(flap, 2 * 5.3 + 100.0, 2.0);
  // Together the two arcs are the whole loop, meeting at the two copies.
  EXPECT_EQ(a.vertices.front(), b.vertices.back());
  EXPECT_EQ(a.vertices.back(), b.vertices.front());
  std::set<engine::VertexId> both(a.vertices.begin(), a.vertices.end());
  both.insert(b.vertices.begin(), b.vertices.end());
  EXPECT_EQ(both.size(), a.vertices.size() + b.vertices.size() - 2);
  engine::ChainSpec whole;
  whole.from = corner;
  whole.loop = true;
  EXPECT_NEAR(tip + flap, engine::chain_length(m, engine::find_boundary_chain(m, whole)), 1e-9);

  // The long way round swaps them; the preview shows what the join will resolve.
  const auto swapped = app::suture_sides(m, {corner, corner, corner, corner}, {true, false}, true);
  ASSERT_EQ(swapped.size(), 2u);
  EXPECT_EQ(chain(m, swapped[0]).vertices, b.vertices);
  EXPECT_EQ(chain(m, swapped[1]).vertices, a.vertices);
  const app::SuturePreview p = app::preview_suture(m, {corner, corner, corner, corner}, {false, false}, true);
  ASSERT_EQ(p.chains.size(), 2u);
  EXPECT_NEAR(p.lengths[0], tip, 1e-12);
  EXPECT_NEAR(p.lengths[1], flap, 1e-12);
  EXPECT_NE(p.lines[0].find("from one lip round to the other"), std::string::npos);
  // Side B is far more than twice side A: the surgeon is warned.
  bool warned = false;
  for (const auto& line : p.lines) warned = warned || line.find("times as long") != std::string::npos;
  EXPECT_TRUE(warned);

  const nlohmann::json op = app::join_op("a", sides[0], sides[1], true);
  EXPECT_EQ(op["chains"][0]["via"], app::point_json(*sides[0].via));
  EXPECT_EQ(op["placement"], "onto_b");
}
