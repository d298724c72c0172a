// surface_path: an incision curve traced over the unrefined mesh as vertex, edge and face
// events, and the shortest edge path (the prototype's snap mode).
#include "surface_path.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/surgery/surface_point.hpp"

namespace sutura::engine::detail {
namespace {

SurfaceMesh strip() {  // 10 x 4 mm in z = 0, 1 mm squares
  StripParams p;
  p.length = 10.0;
  p.width = 4.0;
  p.segments_length = 10;
  p.segments_width = 4;
  return make_strip(p);
}

Vec3 event_position(const SurfaceMesh& m, const PathEvent& e) {
  switch (e.kind) {
    case PathEvent::Kind::Vertex: return m.position(e.vertex);
    case PathEvent::Kind::Edge: return (1.0 - e.t) * m.position(e.edge_a) + e.t * m.position(e.edge_b);
    case PathEvent::Kind::Face: {
      const auto c = m.face_vertices(e.face);
      return e.bary[0] * m.position(c[0]) + e.bary[1] * m.position(c[1]) + e.bary[2] * m.position(c[2]);
    }
  }
  return Vec3::Zero();
}

TEST(SurfacePath, APointIsACornerAnEdgeOrAFacePointBySnap) {
  const SurfaceMesh m = strip();
  SurfacePoint p = closest_surface_point(m, Vec3(3.3, 0.4, 0.0));
  EXPECT_EQ(point_event(m, p, 1e-9).kind, PathEvent::Kind::Face);
  const Vec3 on_vertex = m.position(m.face_vertices(p.face)[0]) + Vec3(1e-4, 1e-4, 0.0);
  p = closest_surface_point(m, on_vertex);
  EXPECT_EQ(point_event(m, p, 0.01).kind, PathEvent::Kind::Vertex);
  EXPECT_EQ(point_event(m, p, 1e-9).kind, PathEvent::Kind::Face);  // a tiny snap only absorbs rounding
  p = closest_surface_point(m, Vec3(3.5, 1.0 + 1e-4, 0.0));  // on the grid line y = 1
  const PathEvent e = point_event(m, p, 0.01);
  EXPECT_EQ(e.kind, PathEvent::Kind::Edge);
  EXPECT_LT((event_position(m, e) - Vec3(3.5, 1.0, 0.0)).norm(), 2e-4);
  // Its faces: the edge's two; a corner's fan; a face point's face.
  EXPECT_EQ(event_faces(m, e).size(), 2u);
  for (FaceId f : event_faces(m, e)) {
    const Eigen::Vector3d b = event_bary(m, e, f);
    const auto c = m.face_vertices(f);
    const Vec3 x = b[0] * m.position(c[0]) + b[1] * m.position(c[1]) + b[2] * m.position(c[2]);
    EXPECT_LT((x - event_position(m, e)).norm(), 1e-12);
  }
}

// A straight cut across the strip crosses every grid line between its ends, in order, on the
// straight line, and consecutive events share a face (what the incision needs to cut).
TEST(SurfacePath, TheTraceCrossesTheMeshAlongTheCurveInOrder) {
  const SurfaceMesh m = strip();
  const SurfacePoint p = closest_surface_point(m, Vec3(1.3, -1.45, 0.0));
  const SurfacePoint q = closest_surface_point(m, Vec3(7.6, 1.35, 0.0));
  const PathEvent pe = point_event(m, p, 1e-3), qe = point_event(m, q, 1e-3);
  const std::vector<PathEvent> events = trace_between(m, p, pe, q, qe, 1e-3, 1);
  ASSERT_GE(events.size(), 9u);  // 6 vertical and 3 horizontal grid lines at least
  const Vec3 d = (q.position - p.position).normalized();
  double along = 0.0;
  std::vector<PathEvent> all{pe};
  all.insert(all.end(), events.begin(), events.end());
  all.push_back(qe);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Vec3 x = event_position(m, all[i]);
    const Vec3 r = x - p.position;
    EXPECT_LT((r - r.dot(d) * d).norm(), 1e-9) << i;  // on the line
    EXPECT_GE(r.dot(d), along - 1e-12) << i;            // in order
    along = r.dot(d);
    if (i + 1 < all.size()) {
      bool shared = false;
      for (FaceId f : event_faces(m, all[i]))
        for (FaceId g : event_faces(m, all[i + 1])) shared = shared || f == g;
      EXPECT_TRUE(shared) << "events " << i << " and " << i + 1 << " share no face";
    }
  }
}

TEST(SurfacePath, TheShortestEdgePathJoinsItsEndsAlongEdges) {
  const SurfaceMesh m = strip();
  VertexId from, to;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3& x = m.position(VertexId(int(v)));
    if ((x - Vec3(0, -2, 0)).norm() < 1e-9) from = VertexId(int(v));
    if ((x - Vec3(10, 2, 0)).norm() < 1e-9) to = VertexId(int(v));
  }
  ASSERT_TRUE(from.valid() && to.valid());
  const std::vector<VertexId> path = shortest_edge_path(m, from, to);
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path.front(), from);
  EXPECT_EQ(path.back(), to);
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    bool edge = false;
    for (FaceId f : m.vertex_faces(path[i])) {
      const auto c = m.face_vertices(f);
      for (int k = 0; k < 3; ++k) edge = edge || c[k] == path[i + 1];
    }
    EXPECT_TRUE(edge) << i;
    length += (m.position(path[i + 1]) - m.position(path[i])).norm();
  }
  const double straight = (m.position(to) - m.position(from)).norm();
  EXPECT_GE(length, straight - 1e-12);
  EXPECT_LE(length, 14.0 + 1e-9);  // never longer than the path along the grid lines
  // Dijkstra: no vertex twice.
  for (std::size_t i = 0; i < path.size(); ++i)
    for (std::size_t j = i + 1; j < path.size(); ++j) EXPECT_NE(path[i], path[j]);
}

}  // namespace
}  // namespace sutura::engine::detail
