#include "sutura/engine/surgery/join.hpp"

#include <algorithm>

#include <gtest/gtest.h>

#include "surgery_fixture.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/patch_plan.hpp"

namespace sutura::engine {
namespace {

using testing::Body;

// Two strips side by side along x with a gap, as one mesh of two components.
SurfaceMesh two_strips(int n1, int n2, double gap = 2.0) {
  const SurfaceMesh a = make_strip({10.0, 4.0, 10, n1});
  const SurfaceMesh b = make_strip({10.0, 4.0, 10, n2});
  std::vector<Vec3> x = a.positions();
  std::vector<FaceIndices> f = a.faces();
  const int off = int(x.size());
  for (const Vec3& p : b.positions()) x.push_back(p + Vec3(10.0 + gap, 0, 0));
  for (FaceIndices t : b.faces()) {
    for (auto& v : t) v += off;
    f.push_back(t);
  }
  return SurfaceMesh(x, f);
}

BoundaryChain facing_edge(const SurfaceMesh& m, double x, double y_from, double y_to) {
  ChainSpec s;
  s.from = Vec3(x, y_from, 0);
  s.to = Vec3(x, y_to, 0);
  return find_boundary_chain(m, s);
}

TEST(Join, TwoStripsWithEqualCountsMergePairwiseAtTheMean) {
  const SurfaceMesh m = two_strips(4, 4);
  // Right edge of strip 1 runs -y -> +y in the boundary direction; left edge of strip 2 +y -> -y.
  const BoundaryChain a = facing_edge(m, 10.0, -2, 2), b = facing_edge(m, 12.0, 2, -2);
  ASSERT_EQ(a.vertices.size(), 5u);
  const JoinResult r = join(m, {{a, b}});
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  EXPECT_EQ(r.mesh.num_vertices(), m.num_vertices() - 5);
  EXPECT_EQ(r.mesh.boundary_loops().size(), 1u);
  EXPECT_EQ(r.merged.size(), 5u);
  for (const VertexId v : r.merged) {
    EXPECT_NEAR(r.mesh.position(v).x(), 11.0, 1e-12);
    EXPECT_EQ(r.maps.vertices[v.index()].kind, VertexOriginKind::Merged);
    EXPECT_EQ(r.maps.vertices[v.index()].parents.size(), 2u);
  }
  EXPECT_EQ(r.sutures[0].inserted_a + r.sutures[0].inserted_b, 0);
  EXPECT_NEAR(r.sutures[0].max_gap, 2.0, 1e-12);
}

TEST(Join, DifferentCountsPairCloseVerticesAndRefineTheRest) {
  const SurfaceMesh m = two_strips(4, 7);
  const BoundaryChain a = facing_edge(m, 10.0, -2, 2), b = facing_edge(m, 12.0, 2, -2);
  const JoinResult r = join(m, {{a, b}});
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  EXPECT_EQ(r.sutures[0].vertices_a, 5u);
  EXPECT_EQ(r.sutures[0].vertices_b, 8u);
  // Arc lengths k/4 and k/7: 1/4 ~ 2/7 and 3/4 ~ 5/7 lie 1/28 apart, within 0.4 of the finer
  // spacing 1/7, and are paired as they are; every other interior vertex gets a partner: b's
  // 1/7, 3/7, 4/7, 6/7 on a, a's 1/2 on b.
  EXPECT_EQ(r.sutures[0].inserted_a, 4);
  EXPECT_EQ(r.sutures[0].inserted_b, 1);
  ASSERT_EQ(r.seams[0].size(), 9u);
  // Each merged vertex is at the mean of its copies: at one chain's vertex arc length when its
  // partner was inserted there, or halfway between a paired 1/4 and 2/7 (3/4 and 5/7). No two
  // seam vertices are closer than 0.4 of the finer spacing (no needle triangles).
  const std::vector<double> expected = {0.0, 1.0 / 7, (0.25 + 2.0 / 7) / 2, 3.0 / 7, 0.5,
                                        4.0 / 7, (0.75 + 5.0 / 7) / 2, 6.0 / 7, 1.0};
  for (std::size_t i = 0; i < r.seams[0].size(); ++i) {
    const double t = (r.mesh.position(r.seams[0][i]).y() + 2.0) / 4.0;  // chain a runs -y -> +y
    EXPECT_NEAR(t, expected[i], 1e-12) << "seam vertex " << i;
    if (i > 0) {
      const double prev = (r.mesh.position(r.seams[0][i - 1]).y() + 2.0) / 4.0;
      EXPECT_GT(t - prev, 0.4 / 7 - 1e-12) << "seam vertex " << i;
    }
  }
}

TEST(Join, OntoBDrawsChainAOntoBAndCarriesAFreeComponentRigidly) {
  const SurfaceMesh m = two_strips(4, 4, 3.0);
  const BoundaryChain a = facing_edge(m, 10.0, -2, 2), b = facing_edge(m, 13.0, 2, -2);
  JoinParams params;
  params.placement = SuturePlacement::OntoB;
  const JoinResult r = join(m, {{a, b}}, params);
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  for (const VertexId v : r.merged) EXPECT_NEAR(r.mesh.position(v).x(), 13.0, 1e-12);
  // Strip 1 follows as a rigid body (a translation by the gap); strip 2 does not move. Every
  // unmerged vertex of strip 1 is reported as displaced.
  const std::size_t n1 = make_strip({10.0, 4.0, 10, 4}).num_vertices();
  std::size_t displaced = 0;
  for (std::size_t v = 0; v < r.maps.vertices.size(); ++v) {
    const auto& o = r.maps.vertices[v];
    if (o.parents.size() != 1) continue;
    const Vec3 before = m.position(o.parents[0]);
    const Vec3 shift = o.parents[0].index() < n1 ? Vec3(3.0, 0, 0) : Vec3::Zero();
    EXPECT_LT((r.mesh.position(VertexId(v)) - before - shift).norm(), 1e-9) << "vertex " << v;
    if (o.parents[0].index() < n1) ++displaced;
  }
  EXPECT_EQ(r.displaced.size(), displaced);
  EXPECT_GT(displaced, 0u);
}

TEST(Join, OntoBKeepsHeldVerticesAndBendsTheFreePartWithoutStretchingIt) {
  // Strip 1 held along x = 0; its right edge is drawn 3 mm across onto strip 2. The free part
  // in between follows with no vertex beyond the held edge or the seam, and no edge of it is
  // stretched much beyond the 30 % the span change forces (10 -> 13 mm) or squeezed.
  const SurfaceMesh m = two_strips(4, 4, 3.0);
  const BoundaryChain a = facing_edge(m, 10.0, -2, 2), b = facing_edge(m, 13.0, 2, -2);
  JoinParams params;
  params.placement = SuturePlacement::OntoB;
  params.held.assign(m.num_vertices(), false);
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    params.held[v] = std::abs(m.position(VertexId(v)).x()) < 1e-12;
  const JoinResult r = join(m, {{a, b}}, params);
  ASSERT_TRUE(r.mesh.validate().ok());
  for (std::size_t v = 0; v < r.maps.vertices.size(); ++v) {
    const auto& o = r.maps.vertices[v];
    const Vec3 x = r.mesh.position(VertexId(v));
    if (o.parents.size() == 1 && params.held[o.parents[0].index()]) {
      EXPECT_EQ(x, m.position(o.parents[0]));
    }
    EXPECT_GE(x.x(), -1e-9);
    EXPECT_LE(x.x(), 23.0 + 1e-9);
  }
  for (const auto& f : r.mesh.faces())
    for (int k = 0; k < 3; ++k) {
      const auto& o0 = r.maps.vertices[f[k]];
      const auto& o1 = r.maps.vertices[f[(k + 1) % 3]];
      if (o0.parents.size() != 1 || o1.parents.size() != 1) continue;
      const double rest = (m.position(o0.parents[0]) - m.position(o1.parents[0])).norm();
      const double now = (r.mesh.position(VertexId(f[k])) - r.mesh.position(VertexId(f[(k + 1) % 3]))).norm();
      EXPECT_GT(now, 0.7 * rest);
      EXPECT_LT(now, 1.4 * rest);
    }
}

TEST(Join, NearlyCoincidentArcLengthsArePairedWithoutInsertion) {
  const SurfaceMesh m = two_strips(4, 4);
  const BoundaryChain a = facing_edge(m, 10.0, -2, 2), b = facing_edge(m, 12.0, 2, -2);
  const JoinResult r = join(m, {{a, b}});
  EXPECT_EQ(r.sutures[0].inserted_a + r.sutures[0].inserted_b, 0);
  EXPECT_EQ(r.seams[0].size(), 5u);
}

TEST(Join, MapsCarryARestStateThatIsStressFreeOnlyAfterCongruentY0) {
  // The joined mesh with carried x0 is stressed (the gap is closed), which is what drives the
  // relaxation; the mapping itself must not create any other stress.
  auto model = make_corotational_shell();
  Body body(two_strips(4, 4));
  const BoundaryChain a = facing_edge(body.mesh, 10.0, -2, 2), b = facing_edge(body.mesh, 12.0, 2, -2);
  const JoinResult r = join(body.mesh, {{a, b}});
  body.apply(r.mesh, r.maps);
  EXPECT_GT(testing::energy_and_force(*model, body).first, 1e-6);
  body.rest = rest_from_state(body.mesh, body.state);
  EXPECT_LT(testing::energy_and_force(*model, body).first, 1e-20);
}

TEST(Join, SlitReJoinedGivesTheOriginalTopologyAndPositions) {
  const SurfaceMesh m = make_tube({4.0, 20.0, 24, 20});
  const IncisionResult cut = incise(m, {Vec3(4, 0, 5), Vec3(0, 4, 14)}, testing::snapped());
  BoundaryChain left{cut.left, false};
  BoundaryChain right{{cut.right.rbegin(), cut.right.rend()}, false};
  const JoinResult r = join(cut.mesh, {{left, right}});
  ASSERT_TRUE(r.mesh.validate().ok());
  EXPECT_EQ(r.mesh.num_vertices(), m.num_vertices());
  EXPECT_EQ(r.mesh.num_faces(), m.num_faces());
  EXPECT_EQ(r.mesh.boundary_loops().size(), m.boundary_loops().size());
  EXPECT_EQ(r.mesh.positions(), m.positions());
  EXPECT_EQ(r.mesh.faces(), m.faces());
}

// A patch is cut at the lips' spacing, but no finer than min_edge_length: a patch far finer
// than its width is laid out over the slit as many thin rows, one of which collapses in the
// relaxation (the fine arch at 0.41 mm with a 4 mm patch).
TEST(Join, APatchIsCutAtTheLipsSpacingButNoFinerThanItsMinimum) {
  const SurfaceMesh t = make_tube({4.0, 20.0, 48, 40});  // 0.5 mm edges
  const IncisionResult cut = incise(t, {Vec3(4, 0, 6.2), Vec3(4, 0, 13.8)});
  PatchPlanParams pp;
  pp.width = 4.0;
  const PatchPlan at_lips = plan_patch(cut.mesh, Vec3(4, 0, 6.2), Vec3(4, 0, 13.8), pp);
  pp.min_edge_length = 0.8;
  const PatchPlan coarser = plan_patch(cut.mesh, Vec3(4, 0, 6.2), Vec3(4, 0, 13.8), pp);
  EXPECT_LT(at_lips.rest.mean_edge_length(), 0.65);
  EXPECT_GT(coarser.rest.mean_edge_length(), 0.7);
  EXPECT_LT(coarser.rest.num_faces(), at_lips.rest.num_faces() / 2);
  pp.min_edge_length = -1.0;
  EXPECT_THROW(plan_patch(cut.mesh, Vec3(4, 0, 6.2), Vec3(4, 0, 13.8), pp), InvalidArgument);
}

TEST(Join, PatchCornerMeetingTwoLipsAndAnotherChainIsAOneToThreeMapping) {
  // Open a tube end with an incision, insert a triangular gusset, then suture the widened end
  // loop to another tube's end: the gusset's base corners carry three rest positions.
  const SurfaceMesh t1 = make_tube({3.0, 10.0, 24, 10});
  const IncisionResult cut = incise(t1, {Vec3(3, 0, 10), Vec3(3, 0, 5)}, testing::snapped());
  PatchPlanParams pp;
  pp.shape = PatchShape::Triangle;
  pp.width = 2.0;
  const PatchPlan plan = plan_patch(cut.mesh, Vec3(3, 0, 10), Vec3(3, 0, 5), pp);
  // Host + patch as one mesh.
  std::vector<Vec3> x = cut.mesh.positions();
  std::vector<FaceIndices> f = cut.mesh.faces();
  const int off = int(x.size());
  for (const Vec3& p : plan.placed.positions()) x.push_back(p);
  for (FaceIndices t : plan.placed.faces()) {
    for (auto& v : t) v += off;
    f.push_back(t);
  }
  const SurfaceMesh both(x, f);
  auto shift = [&](BoundaryChain c) {
    for (auto& v : c.vertices) v = VertexId(v.value + off);
    return c;
  };
  const JoinResult j1 =
      join(both, {{plan.lip_left, shift(plan.edge_left)}, {plan.lip_right, shift(plan.edge_right)}});
  ASSERT_TRUE(j1.mesh.validate().ok()) << j1.mesh.validate().summary();
  // Second tube in line; its z = 10 end loop is sutured to the widened z = 10 loop.
  const SurfaceMesh t2 = make_tube({3.4, 10.0, 26, 10});
  std::vector<Vec3> x2 = j1.mesh.positions();
  std::vector<FaceIndices> f2 = j1.mesh.faces();
  const int off2 = int(x2.size());
  for (const Vec3& p : t2.positions()) x2.push_back(p + Vec3(0, 0, 10.5));
  for (FaceIndices t : t2.faces()) {
    for (auto& v : t) v += off2;
    f2.push_back(t);
  }
  const SurfaceMesh joined(x2, f2);
  ChainSpec end1, end2;
  end1.loop = end2.loop = true;
  end1.from = Vec3(-3, 0, 10);
  end2.from = Vec3(-3.4, 0, 10.5);
  const JoinResult j2 =
      join(joined, {{find_boundary_chain(joined, end1), find_boundary_chain(joined, end2)}});
  ASSERT_TRUE(j2.mesh.validate().ok()) << j2.mesh.validate().summary();
  // The gusset's base corners: each merged first with a lip's end copy, then with a vertex
  // of the second tube's end loop, i.e. one simulated vertex with three rest positions.
  for (const VertexId corner : {plan.edge_left.vertices.back(), plan.edge_right.vertices.front()}) {
    VertexId in_j1;
    for (std::size_t v = 0; v < j1.maps.vertices.size(); ++v)
      for (const VertexId p : j1.maps.vertices[v].parents)
        if (p.value == corner.value + off) in_j1 = VertexId(v);
    ASSERT_TRUE(in_j1.valid());
    EXPECT_EQ(j1.maps.vertices[in_j1.index()].kind, VertexOriginKind::Merged);
    ASSERT_EQ(j1.maps.vertices[in_j1.index()].parents.size(), 2u);  // patch corner + lip end
    // In the second join it is merged with exactly one vertex of the other loop (weight 1/2
    // on it): 2 + 1 = 3 rest positions for one simulated vertex.
    double weight = 0.0;
    VertexOriginKind kind = VertexOriginKind::Copy;
    for (const auto& o : j2.maps.vertices)
      for (std::size_t k = 0; k < o.parents.size(); ++k)
        if (o.parents[k] == in_j1 && o.weights[k] > weight) weight = o.weights[k], kind = o.kind;
    EXPECT_EQ(kind, VertexOriginKind::Merged);
    EXPECT_DOUBLE_EQ(weight, 0.5);
  }
  EXPECT_EQ(j2.mesh.boundary_loops().size(), 2u);  // the two far ends
}

TEST(Join, ClosingASmallFanAtASharedEndWidensItFirst) {
  // A sheet whose edges e-x and y-e are sutured (x to y): e's fan has only two faces, which
  // closing into a cone would stack onto one edge; the join widens it.
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0),
                               Vec3(0, 2, 0), Vec3(0, 1, 0), Vec3(1.2, 0.9, 0.3)};
  //                             e=0          x=1           x2=2          z=3
  //                             y2=4         y=5           w=6
  const SurfaceMesh m(x, {{0, 1, 6}, {1, 2, 6}, {2, 3, 6}, {6, 3, 4}, {6, 4, 5}, {0, 6, 5}});
  const BoundaryChain a{{VertexId(0), VertexId(1)}, false};
  const BoundaryChain b{{VertexId(5), VertexId(0)}, false};
  const JoinResult r = join(m, {{a, b}});
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  EXPECT_FALSE(r.mesh.is_boundary(VertexId(0)));  // e is now inside the closed cone
  EXPECT_GE(r.mesh.vertex_faces(VertexId(0)).size(), 3u);
  // The face with the wider angle at e (e-w-y: 54.0 against 38.3 degrees for e-x-w) is split
  // where that angle's bisector meets its outer edge w-y, dividing it as |ew| : |ey|.
  const double t = (x[6] - x[0]).norm() / ((x[6] - x[0]).norm() + (x[5] - x[0]).norm());
  int on_wy = 0, on_xw = 0;
  for (const VertexOrigin& o : r.maps.vertices) {
    if (o.kind != VertexOriginKind::Interpolated || o.parents.size() != 2) continue;
    const int p0 = o.parents[0].value, p1 = o.parents[1].value;
    if ((p0 == 1 && p1 == 6) || (p0 == 6 && p1 == 1)) ++on_xw;
    if ((p0 == 6 && p1 == 5) || (p0 == 5 && p1 == 6)) {
      ++on_wy;
      EXPECT_NEAR(o.weights[p0 == 5 ? 0 : 1], t, 1e-12);
    }
  }
  EXPECT_EQ(on_wy, 1);
  EXPECT_EQ(on_xw, 0);
}

TEST(Join, RejectsHeldFlagsOfTheWrongSize) {
  const SurfaceMesh m = two_strips(4, 4);
  const BoundaryChain a = facing_edge(m, 10.0, -2, 2), b = facing_edge(m, 12.0, 2, -2);
  JoinParams params;
  params.placement = SuturePlacement::OntoB;
  params.held.assign(3, true);
  EXPECT_THROW(join(m, {{a, b}}, params), InvalidArgument);
  EXPECT_THROW(parse_suture_placement("middle"), InvalidArgument);
  EXPECT_EQ(parse_suture_placement("onto_b"), SuturePlacement::OntoB);
}

TEST(Join, RejectsBadChains) {
  const SurfaceMesh m = two_strips(4, 4);
  const BoundaryChain a = facing_edge(m, 10.0, -2, 2), b = facing_edge(m, 12.0, 2, -2);
  auto message = [&](const std::vector<SuturePair>& pairs) {
    try {
      join(m, pairs);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{a, a}}).find("overlaps"), std::string::npos);
  BoundaryChain loop = boundary_chain(m, b.vertices.front(), b.vertices.front());
  EXPECT_NE(message({{a, loop}}).find("closed loop"), std::string::npos);
  BoundaryChain reversed{{a.vertices.rbegin(), a.vertices.rend()}, false};
  EXPECT_NE(message({{reversed, b}}).find("boundary direction"), std::string::npos);
  EXPECT_NE(message({}).find("at least one pair"), std::string::npos);
}

TEST(BoundaryChainSpec, ResolvesCoincidentLipsByViaPoint) {
  const SurfaceMesh tube = make_tube({4.0, 20.0, 24, 20});
  const IncisionResult cut = incise(tube, {Vec3(4, 0, 0), Vec3(4, 0, 10)}, testing::snapped());
  ChainSpec s;
  s.from = Vec3(4, 0, 0);
  s.to = Vec3(4, 0, 10);
  const BoundaryChain shortest = find_boundary_chain(cut.mesh, s);
  EXPECT_EQ(shortest.vertices.size(), cut.left.size());
  s.via = Vec3(-4, 0, 0);  // the far side of the end loop
  const BoundaryChain around = find_boundary_chain(cut.mesh, s);
  EXPECT_GT(around.vertices.size(), cut.left.size());
  s.from = Vec3(4, 0, 30);
  EXPECT_THROW(find_boundary_chain(cut.mesh, s), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
