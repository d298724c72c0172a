// The suture tool's reading of clicks: each side's two ends in either order, the shorter arc
// between them (or the long way round), side B never on side A's arc, recorded in the
// boundary direction; and a click near a boundary corner picks the corner.
#include <gtest/gtest.h>

#include <set>

#include "../../ui/src/op_builders.hpp"
#include "../../ui/src/scene_picker.hpp"
#include "../../ui/src/suture_preview.hpp"
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

engine::BoundaryChain chain(const engine::SurfaceMesh& m, const Vec3& from, const Vec3& to) {
  engine::ChainSpec s;
  s.from = from;
  s.to = to;
  return engine::find_boundary_chain(m, s);
}

}  // namespace

TEST(SuturePreview, BothSidesClickedTheSameWayAreOrientedForTheJoin) {
  const engine::SurfaceMesh m = two_strips();
  // Facing edges of the strips (x = 18 and x = 22), both clicked from y = -5 to y = 5. The left
  // strip's boundary runs up its right edge, the right strip's down its left edge.
  const std::vector<Vec3> clicks = {{18, -5, 0}, {18, 5, 0}, {22, -5, 0}, {22, 5, 0}};
  const auto oriented = ui::orient_suture_clicks(m, clicks);
  ASSERT_EQ(oriented.size(), 4u);
  EXPECT_EQ(oriented[0], clicks[0]);
  EXPECT_EQ(oriented[1], clicks[1]);
  EXPECT_EQ(oriented[2], clicks[3]);  // side B swapped: as clicked it is the long way round
  EXPECT_EQ(oriented[3], clicks[2]);
  const ui::SuturePreview p = ui::preview_suture(m, clicks);
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
  const auto reversed = ui::orient_suture_clicks(m, {clicks[1], clicks[0], clicks[2], clicks[3]});
  EXPECT_EQ(reversed, oriented);
}

TEST(SuturePreview, TheLongWayRoundIsTakenOnlyWhenAskedFor) {
  const engine::SurfaceMesh m = two_strips();
  const std::vector<Vec3> a = {{18, -5, 0}, {18, 5, 0}};
  const auto shorter = ui::orient_suture_clicks(m, a);
  EXPECT_NEAR(engine::chain_length(m, chain(m, shorter[0], shorter[1])), 10.0, 1e-12);
  const auto longer = ui::orient_suture_clicks(m, a, {true, false});
  EXPECT_NEAR(engine::chain_length(m, chain(m, longer[0], longer[1])), 46.0, 1e-12);
  // One click per side so far: nothing to orient.
  EXPECT_EQ(ui::orient_suture_clicks(m, {a[0]}), std::vector<Vec3>{a[0]});
}

TEST(SuturePreview, ClickingBothLipsFromTheSameEndGivesTheTwoLips) {
  engine::StripParams sp;
  const engine::IncisionResult cut = engine::incise(engine::make_strip(sp), {{10, 0.3, 0}, {30, 0.3, 0}});
  const engine::SurfaceMesh& m = cut.mesh;
  const Vec3 first = m.position(cut.left.front()), last = m.position(cut.left.back());
  // Both sides clicked at the same two ends (the slit's tips), in the same order.
  const auto oriented = ui::orient_suture_clicks(m, {first, last, first, last});
  const engine::BoundaryChain a = chain(m, oriented[0], oriented[1]);
  const engine::BoundaryChain b = chain(m, oriented[2], oriented[3]);
  const auto as_set = [](const std::vector<engine::VertexId>& v) {
    return std::set<engine::VertexId>(v.begin(), v.end());
  };
  const std::set<engine::VertexId> left = as_set(cut.left), right = as_set(cut.right);
  EXPECT_NE(as_set(a.vertices), as_set(b.vertices));
  EXPECT_TRUE((as_set(a.vertices) == left && as_set(b.vertices) == right) ||
              (as_set(a.vertices) == right && as_set(b.vertices) == left));
  const ui::SuturePreview p = ui::preview_suture(m, {first, last, first, last});
  ASSERT_EQ(p.meeting_ends.size(), 2u);
  EXPECT_EQ(p.meeting_ends[0][0], p.meeting_ends[0][1]);  // a slit: its ends are shared
}

TEST(ScenePicker, AClickNearACornerPicksIt) {
  const engine::SurfaceMesh m = two_strips();
  ui::ScenePicker picker;
  picker.rebuild({&m});
  // 0.45 mm from the boundary vertex (18, -4), 1.26 mm from the corner (18, -5), seen from 10 mm.
  const engine::Ray ray{Vec3(17.6, -3.8, 10), Vec3(0, 0, -1)};
  const auto plain = picker.pick(ray);
  ASSERT_TRUE(plain);
  EXPECT_EQ(m.position(plain->boundary_vertex), Vec3(18, -4, 0));
  // A snap angle reaching 1.5 mm at 10 mm: the corner wins.
  const auto snapped = picker.pick(ray, std::atan(0.15));
  ASSERT_TRUE(snapped);
  EXPECT_EQ(m.position(snapped->boundary_vertex), Vec3(18, -5, 0));
  EXPECT_EQ(snapped->boundary_loop, plain->boundary_loop);
  // A reach of 1.0 mm does not get there: the nearest boundary vertex again.
  EXPECT_EQ(m.position(picker.pick(ray, std::atan(0.10))->boundary_vertex), Vec3(18, -4, 0));
  // The middle of a straight edge is no corner: (18, 0) is taken only when it is the nearest.
  const auto middle = picker.pick({Vec3(17.6, 0.3, 10), Vec3(0, 0, -1)}, std::atan(0.3));
  ASSERT_TRUE(middle);
  EXPECT_EQ(m.position(middle->boundary_vertex), Vec3(18, 0, 0));
}

TEST(SuturePreview, TheSameVertexTwiceIsItsWholeLoop) {
  engine::TubeParams tp;
  tp.radius = 4.0;
  tp.length = 20.0;
  const engine::SurfaceMesh m = engine::make_tube(tp);
  const Vec3 bottom = m.position(m.boundary_loops()[0][3]);
  const Vec3 top = m.position(m.boundary_loops()[1][5]);
  const std::vector<Vec3> clicks = {bottom, bottom, top, top};
  EXPECT_EQ(ui::orient_suture_clicks(m, clicks), clicks);  // loops are not reordered
  const ui::SuturePreview p = ui::preview_suture(m, clicks);
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
  const nlohmann::json op = ui::join_op("a", {bottom, bottom}, {top, top}, false);
  EXPECT_EQ(op["chains"][0], nlohmann::json({{"loop", {bottom.x(), bottom.y(), bottom.z()}}}));
  EXPECT_EQ(op["chains"][1], nlohmann::json({{"loop", {top.x(), top.y(), top.z()}}}));
  const nlohmann::json open = ui::join_op("a", {bottom, top}, {top, bottom}, false);
  EXPECT_TRUE(open["chains"][0].contains("from"));
}
