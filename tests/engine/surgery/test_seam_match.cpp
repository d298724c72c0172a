#include "sutura/engine/surgery/seam_match.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/surgery/incise.hpp"

namespace sutura::engine {
namespace {

// Two components: `first` as given, `second` moved by `offset`.
SurfaceMesh side_by_side(const SurfaceMesh& first, const SurfaceMesh& second, const Vec3& offset) {
  std::vector<Vec3> x = first.positions();
  std::vector<FaceIndices> f = first.faces();
  const int off = int(x.size());
  for (const Vec3& p : second.positions()) x.push_back(p + offset);
  for (FaceIndices t : second.faces()) {
    for (auto& v : t) v += off;
    f.push_back(t);
  }
  return SurfaceMesh(x, f);
}

BoundaryChain chain(const SurfaceMesh& m, const Vec3& from, const Vec3& to) {
  ChainSpec s;
  s.from = from;
  s.to = to;
  return find_boundary_chain(m, s);
}

BoundaryChain loop(const SurfaceMesh& m, const Vec3& near) {
  ChainSpec s;
  s.from = near;
  s.loop = true;
  s.max_distance = 5.0;
  return find_boundary_chain(m, s);
}

// Two strips 10 x 4 mm facing across a 0.01 mm gap (so that the joined shape is the rest
// shape), their facing edges cut into 4 and 7 pieces.
constexpr double kGap = 0.01;
struct Strips {
  SurfaceMesh mesh = side_by_side(make_strip({10.0, 4.0, 10, 4}), make_strip({10.0, 4.0, 10, 7}),
                                  Vec3(10.0 + kGap, 0, 0));
  SuturePair pair{chain(mesh, {10, -2, 0}, {10, 2, 0}),
                  chain(mesh, {10 + kGap, 2, 0}, {10 + kGap, -2, 0})};
};

// Matches the strips' seam with `params`: chain b keeps `kept` (a vertex of the input) as one
// of its common points, both chains get one count, and the join inserts nothing.
void expect_breakpoint_kept(const Strips& s, const ResampleChainsParams& params, VertexId kept) {
  const MatchedSeams m = match_seams(s.mesh, {s.pair}, params);
  bool found = false;
  for (const VertexId v : m.pairs[0].b.vertices) found = found || m.edit.mesh.position(v) == s.mesh.position(kept);
  EXPECT_TRUE(found);
  ASSERT_EQ(m.pairs[0].a.vertices.size(), m.pairs[0].b.vertices.size());
  const SutureReport r = join(m.edit.mesh, m.pairs).sutures[0];
  EXPECT_EQ(r.inserted_a + r.inserted_b, 0);
}

TEST(SeamMatch, ChainsOfDifferentSpacingsGetOneCountAndTheJoinInsertsNothing) {
  const Strips s;
  ASSERT_EQ(s.pair.a.vertices.size(), 5u);
  ASSERT_EQ(s.pair.b.vertices.size(), 8u);
  const MatchedSeams m = match_seams(s.mesh, {s.pair}, {});
  ASSERT_TRUE(m.edit.mesh.validate().ok()) << m.edit.mesh.validate().summary();
  const SuturePair& p = m.pairs[0];
  ASSERT_EQ(p.a.vertices.size(), p.b.vertices.size());
  // The seam spacing is the faces' beside it (1 mm and 4/7 mm; the median lies between), so
  // the 4 mm seam has between 4 and 7 pieces.
  EXPECT_GE(p.a.vertices.size(), 5u);
  EXPECT_LE(p.a.vertices.size(), 8u);
  // Every point on its old chain (x = 10 and x = 10.01), evenly spaced, the ends kept.
  const std::size_t n = p.a.vertices.size() - 1;
  for (std::size_t k = 0; k <= n; ++k) {
    const Vec3 a = m.edit.mesh.position(p.a.vertices[k]), b = m.edit.mesh.position(p.b.vertices[n - k]);
    EXPECT_NEAR(a.x(), 10.0, 1e-12);
    EXPECT_NEAR(b.x(), 10.0 + kGap, 1e-12);
    EXPECT_NEAR(a.y(), -2.0 + 4.0 * double(k) / double(n), 1e-12);
    EXPECT_NEAR(b.y(), a.y(), 1e-12);
  }
  for (const JoinPairing pairing : {JoinPairing::ArcLength, JoinPairing::InOrder}) {
    JoinParams jp;
    jp.pairing = pairing;
    const JoinResult j = join(m.edit.mesh, m.pairs, jp);
    EXPECT_EQ(j.sutures[0].inserted_a + j.sutures[0].inserted_b, 0);
    EXPECT_EQ(j.merged.size(), n + 1);
  }
  // Without matching, the pairing inserts partners next to existing vertices.
  const JoinResult raw = join(s.mesh, {s.pair});
  EXPECT_GT(raw.sutures[0].inserted_a, 0);
  EXPECT_GE(m.edit.after.min_angle_deg, 20.0);
  EXPECT_GE(mesh_quality(join(m.edit.mesh, m.pairs).mesh).min_angle_deg, 20.0);
  EXPECT_LT(mesh_quality(raw.mesh).min_angle_deg, 20.0);
}

TEST(SeamMatch, LoopsOfTwoTubesAnastomoseWithoutSlivers) {
  // Two tube ends facing each other, 12 and 17 segments around.
  const SurfaceMesh a = make_tube({3.0, 10.0, 12, 6}), b = make_tube({3.0, 10.0, 17, 9});
  const SurfaceMesh mesh = side_by_side(a, b, Vec3(0, 0, 11.0));
  const SuturePair pair{loop(mesh, {3, 0, 10}), loop(mesh, {3, 0, 11})};
  ASSERT_TRUE(pair.a.closed);
  ASSERT_EQ(pair.a.vertices.size(), 12u);
  ASSERT_EQ(pair.b.vertices.size(), 17u);
  const MatchedSeams m = match_seams(mesh, {pair}, {});
  ASSERT_EQ(m.pairs[0].a.vertices.size(), m.pairs[0].b.vertices.size());
  EXPECT_TRUE(m.pairs[0].a.closed);
  // The loops' first vertices are kept (they are the partners that start the suture).
  EXPECT_EQ(m.edit.mesh.position(m.pairs[0].a.vertices[0]), mesh.position(pair.a.vertices[0]));
  EXPECT_EQ(m.edit.mesh.position(m.pairs[0].b.vertices[0]), mesh.position(pair.b.vertices[0]));
  // Points on the old polygons: at radius 3 at the vertices, inside it only along a chord.
  for (const auto* c : {&m.pairs[0].a, &m.pairs[0].b})
    for (const VertexId v : c->vertices) {
      const Vec3 p = m.edit.mesh.position(v);
      EXPECT_LE(std::hypot(p.x(), p.y()), 3.0 + 1e-12);
      EXPECT_GE(std::hypot(p.x(), p.y()), 3.0 * std::cos(M_PI / 12.0) - 1e-12);
    }
  const JoinResult j = join(m.edit.mesh, m.pairs);
  EXPECT_EQ(j.sutures[0].inserted_a + j.sutures[0].inserted_b, 0);
  EXPECT_GE(m.edit.after.min_angle_deg, 20.0);
  EXPECT_LT(mesh_quality(join(mesh, {pair}).mesh).min_angle_deg, 20.0);
}

TEST(SeamMatch, AHeldChainVertexIsKeptAsABreakpointAndPairedAtItsFraction) {
  const Strips s;
  std::vector<bool> held(s.mesh.num_vertices(), false);
  const VertexId kept = s.pair.b.vertices[2];  // at 2/7 of chain b
  held[kept.index()] = true;
  ResampleChainsParams params;
  params.constrained_vertices = held;
  expect_breakpoint_kept(s, params, kept);
}

TEST(SeamMatch, TheEndOfAConstrainedPolylineOnAChainIsABreakpoint) {
  // An earlier seam (an interior constrained edge) ends on chain b: the remesh keeps that end,
  // so it must be one of the common points, or the join would insert a partner beside it.
  const Strips s;
  const VertexId end = s.pair.b.vertices[3];
  VertexId inner;
  for (const VertexId v : s.mesh.vertex_neighbors(end))
    if (!s.mesh.is_boundary(v)) inner = v;
  ASSERT_TRUE(inner.valid());
  ResampleChainsParams params;
  params.constrained_edges = {{end, inner}};
  expect_breakpoint_kept(s, params, end);
}

TEST(SeamMatch, TheTipOfASlitOnAChainIsKeptAsABreakpoint) {
  // A strip slit from its right edge 3.7 mm inward; chain a runs up that edge, along the
  // lower lip to the slit's tip, back along the upper lip and on up the edge (11.4 mm, the
  // tip at 0.52 of it), sewn to the 11.4 mm edge of a plain strip. The tip must stay where
  // it was cut: as a breakpoint.
  const IncisionResult slit = incise(make_strip({10.0, 4.0, 20, 8}), {Vec3(10, 0.2, 0), Vec3(6.3, 0.2, 0)});
  const SurfaceMesh mesh = side_by_side(slit.mesh, make_strip({10.0, 11.4, 10, 12}), Vec3(10.0 + kGap, 0, 0));
  ChainSpec a;
  a.from = {10, -2, 0};
  a.to = {10, 2, 0};
  a.via = Vec3(6.3, 0.2, 0);
  const SuturePair pair{find_boundary_chain(mesh, a), chain(mesh, {10 + kGap, 5.7, 0}, {10 + kGap, -5.7, 0})};
  VertexId tip;
  for (const VertexId v : pair.a.vertices)
    if ((mesh.position(v) - Vec3(6.3, 0.2, 0)).norm() < 1e-9) tip = v;
  ASSERT_TRUE(tip.valid());

  // The deepest point of the slit after matching (the tip's x while the tip is kept).
  const auto deepest = [&](const MatchedSeams& m) {
    double x = 10.0;
    for (const VertexId v : m.pairs[0].a.vertices) x = std::min(x, m.edit.mesh.position(v).x());
    return x;
  };
  const MatchedSeams m = match_seams(mesh, {pair}, {});
  ASSERT_TRUE(m.edit.mesh.validate().ok()) << m.edit.mesh.validate().summary();
  ASSERT_EQ(m.pairs[0].a.vertices.size(), m.pairs[0].b.vertices.size());
  bool kept = false;
  for (const VertexId v : m.pairs[0].a.vertices) kept = kept || m.edit.mesh.position(v) == mesh.position(tip);
  EXPECT_TRUE(kept);
  EXPECT_EQ(deepest(m), mesh.position(tip).x());
  const SutureReport r = join(m.edit.mesh, m.pairs).sutures[0];
  EXPECT_EQ(r.inserted_a + r.inserted_b, 0);

  // Without the corner rule the tip is collapsed into a lip neighbour: the slit is shorter.
  ResampleChainsParams no_corners;
  no_corners.corner_turn_deg = 1000.0;
  EXPECT_GT(deepest(match_seams(mesh, {pair}, no_corners)), mesh.position(tip).x() + 0.1);
  ResampleChainsParams bad;
  bad.corner_turn_deg = -1.0;
  EXPECT_THROW(match_seams(mesh, {pair}, bad), InvalidArgument);
}

TEST(SeamMatch, FrozenFacesAreLeftAsTheyAreAndTheirChainEdgesWhole) {
  const Strips s;
  // Freeze the faces of strip b along its chain edge between its vertices 2 and 3.
  std::vector<bool> frozen(s.mesh.num_faces(), false);
  const VertexId u = s.pair.b.vertices[2], w = s.pair.b.vertices[3];
  for (std::size_t f = 0; f < s.mesh.num_faces(); ++f) {
    const FaceIndices& t = s.mesh.faces()[f];
    const bool touches = std::count(t.begin(), t.end(), u.value) + std::count(t.begin(), t.end(), w.value) > 0;
    if (touches) frozen[f] = true;
  }
  ResampleChainsParams params;
  params.frozen_faces = frozen;
  const MatchedSeams m = match_seams(s.mesh, {s.pair}, params);
  ASSERT_TRUE(m.edit.mesh.validate().ok());
  // Every frozen face is still there, corner for corner.
  const auto& x0 = s.mesh.positions();
  const auto& x1 = m.edit.mesh.positions();
  for (std::size_t f = 0; f < frozen.size(); ++f) {
    if (!frozen[f]) continue;
    bool found = false;
    for (const FaceIndices& t : m.edit.mesh.faces()) {
      bool same = true;
      for (int k = 0; k < 3; ++k) same = same && x1[std::size_t(t[k])] == x0[std::size_t(s.mesh.faces()[f][k])];
      found = found || same;
    }
    EXPECT_TRUE(found) << "frozen face " << f;
  }
  // u and w are consecutive common points of chain b, with their partners on a.
  const auto& b = m.pairs[0].b.vertices;
  std::size_t iu = b.size(), iw = b.size();
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (x1[b[k].index()] == x0[u.index()]) iu = k;
    if (x1[b[k].index()] == x0[w.index()]) iw = k;
  }
  ASSERT_LT(iu, b.size());
  ASSERT_LT(iw, b.size());
  EXPECT_EQ(iw, iu + 1);
  ASSERT_EQ(m.pairs[0].a.vertices.size(), b.size());
  EXPECT_EQ(join(m.edit.mesh, m.pairs).sutures[0].inserted_a, 0);
  params.frozen_faces.assign(3, false);
  EXPECT_THROW(match_seams(s.mesh, {s.pair}, params), InvalidArgument);
}

TEST(SeamMatch, AFrozenChainEdgeIsSpacedByItsRestLength) {
  // Chain b's edge (u, w), 4/7 mm now, is 12/7 mm at rest (a patch laid compressed): b then
  // measures 4 + 8/7 = 36/7 mm, u lies at 2/9 of it and w at 5/9, and their partners on a
  // (which runs the other way) at 7/9 and 4/9 of a's 4 mm, not at u's and w's positions. At
  // rest the edge is longer than 4/3 of the seam spacing, so it is split at its middle, whose
  // partner lies at 5.5/9.
  const Strips s;
  const VertexId u = s.pair.b.vertices[2], w = s.pair.b.vertices[3];
  ResampleChainsParams params;
  params.frozen_faces.assign(s.mesh.num_faces(), false);
  for (std::size_t f = 0; f < s.mesh.num_faces(); ++f) {
    const FaceIndices& t = s.mesh.faces()[f];
    std::array<double, 3> rest{};
    for (int k = 0; k < 3; ++k) {
      const VertexId from(t[k]), to(t[(k + 1) % 3]);
      rest[std::size_t(k)] = (s.mesh.position(to) - s.mesh.position(from)).norm();
      if (from == u && to == w) rest[std::size_t(k)] *= 3.0, params.frozen_faces[f] = true;
    }
    params.rest_edge_lengths.push_back(rest);
  }
  ASSERT_EQ(std::count(params.frozen_faces.begin(), params.frozen_faces.end(), true), 1);
  const MatchedSeams m = match_seams(s.mesh, {s.pair}, params);
  ASSERT_TRUE(m.edit.mesh.validate().ok());
  const auto& a = m.pairs[0].a.vertices;
  const auto& b = m.pairs[0].b.vertices;
  ASSERT_EQ(a.size(), b.size());
  const std::size_t n = b.size() - 1;
  std::size_t iu = b.size(), iw = b.size();
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (m.edit.mesh.position(b[k]) == s.mesh.position(u)) iu = k;
    if (m.edit.mesh.position(b[k]) == s.mesh.position(w)) iw = k;
  }
  ASSERT_LT(iu, b.size());
  ASSERT_EQ(iw, iu + 2);
  EXPECT_NEAR((m.edit.mesh.position(b[iu + 1]) - 0.5 * (s.mesh.position(u) + s.mesh.position(w))).norm(), 0.0, 1e-12);
  EXPECT_NEAR(m.edit.mesh.position(a[n - iu]).y(), -2.0 + 4.0 * 7.0 / 9.0, 1e-12);
  EXPECT_NEAR(m.edit.mesh.position(a[n - iu - 1]).y(), -2.0 + 4.0 * 5.5 / 9.0, 1e-12);
  EXPECT_NEAR(m.edit.mesh.position(a[n - iw]).y(), -2.0 + 4.0 * 4.0 / 9.0, 1e-12);
  // Paired in order, nothing is inserted; by arc length, the spacings no longer agree.
  JoinParams in_order;
  in_order.pairing = JoinPairing::InOrder;
  const SutureReport r = join(m.edit.mesh, m.pairs, in_order).sutures[0];
  EXPECT_EQ(r.inserted_a + r.inserted_b, 0);
  // One entry per face, or none.
  params.rest_edge_lengths.pop_back();
  EXPECT_THROW(match_seams(s.mesh, {s.pair}, params), InvalidArgument);
}

TEST(SeamMatch, ResampleChainsChecksItsInput) {
  const Strips s;
  ResampleChainsParams p;
  p.target_edge_length = 1.0;
  EXPECT_THROW(resample_chains(s.mesh, {{s.pair.a, {0.5, 0.25}}}, p), InvalidArgument);
  EXPECT_THROW(resample_chains(s.mesh, {{s.pair.a, {0.0}}}, p), InvalidArgument);
  BoundaryChain backwards = s.pair.a;
  std::reverse(backwards.vertices.begin(), backwards.vertices.end());
  EXPECT_THROW(resample_chains(s.mesh, {{backwards, {0.5}}}, p), InvalidArgument);
  p.target_edge_length = 0.0;
  EXPECT_THROW(resample_chains(s.mesh, {{s.pair.a, {0.5}}}, p), InvalidArgument);
  EXPECT_EQ(equal_fractions(4), (std::vector<double>{0.25, 0.5, 0.75}));
}

TEST(SeamMatch, InOrderPairingRefusesChainsOfDifferentCounts) {
  const Strips s;
  JoinParams jp;
  jp.pairing = JoinPairing::InOrder;
  EXPECT_THROW(join(s.mesh, {s.pair}, jp), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
