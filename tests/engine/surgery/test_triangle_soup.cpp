// TriangleSoup: the edge and face splits an incision makes before the mesh is rebuilt, each
// keeping its origin in the mesh the soup was made from.
#include "triangle_soup.hpp"

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine::detail {
namespace {

SurfaceMesh square() {  // 2 x 2 mm, two triangles
  StripParams p;
  p.length = 2.0;
  p.width = 2.0;
  p.segments_length = 1;
  p.segments_width = 1;
  return make_strip(p);
}

double area(const TriangleSoup& s, int f) {
  const FaceIndices& i = s.face(f);
  return 0.5 * (s.position(i[1]) - s.position(i[0])).cross(s.position(i[2]) - s.position(i[0])).norm();
}

// Every soup face lies in its original face where its barycentrics say, and the faces of one
// original face tile it (their areas add up to its area).
void expect_tiles(const SurfaceMesh& m, const TriangleSoup& s) {
  for (std::size_t p = 0; p < m.num_faces(); ++p) {
    const FaceId parent{int(p)};
    double sum = 0.0;
    for (int f : s.faces_of(parent)) {
      sum += area(s, f);
      const auto corners = m.face_vertices(parent);
      const Eigen::Matrix3d& b = s.maps().faces[f].bary;
      for (int k = 0; k < 3; ++k) {
        Vec3 x = Vec3::Zero();
        for (int j = 0; j < 3; ++j) x += b(k, j) * m.position(corners[j]);
        EXPECT_LT((x - s.position(s.face(f)[k])).norm(), 1e-12) << "face " << f << " corner " << k;
      }
    }
    EXPECT_NEAR(sum, m.face_area(parent), 1e-12) << "parent " << p;
  }
}

TEST(TriangleSoup, SplittingAnEdgeSplitsBothFacesAndRemembersTheEnds) {
  const SurfaceMesh m = square();
  TriangleSoup s(m);
  ASSERT_EQ(s.num_faces(), 2u);
  // The diagonal is the one edge the two faces share.
  int u = -1, v = -1;
  for (int a = 0; a < 4 && u < 0; ++a)
    for (int b = 0; b < 4; ++b)
      if (a != b && s.face_with_edge(a, b) >= 0 && s.face_with_edge(b, a) >= 0) {
        u = a, v = b;
        break;
      }
  ASSERT_GE(u, 0);
  const int w = s.split_edge(u, v, 0.25);
  EXPECT_EQ(s.num_vertices(), 5u);
  EXPECT_EQ(s.num_faces(), 4u);
  EXPECT_LT((s.position(w) - (0.75 * s.position(u) + 0.25 * s.position(v))).norm(), 1e-15);
  const VertexOrigin& o = s.maps().vertices[w];
  EXPECT_EQ(o.kind, VertexOriginKind::Interpolated);
  ASSERT_EQ(o.parents.size(), 2u);
  EXPECT_FALSE(s.has_edge(u, v));
  EXPECT_TRUE(s.has_edge(u, w) && s.has_edge(w, v));
  expect_tiles(m, s);
  EXPECT_THROW(s.split_edge(u, v, 0.5), InvalidArgument);  // no longer an edge
}

TEST(TriangleSoup, SplittingABoundaryEdgeAndAFaceKeepsTheTiling) {
  const SurfaceMesh m = square();
  TriangleSoup s(m);
  int u = -1, v = -1;  // a boundary edge: one face only
  for (int a = 0; a < 4 && u < 0; ++a)
    for (int b = 0; b < 4; ++b)
      if (a != b && s.face_with_edge(a, b) >= 0 && s.face_with_edge(b, a) < 0) {
        u = a, v = b;
        break;
      }
  ASSERT_GE(u, 0);
  s.split_edge(u, v, 0.5);
  EXPECT_EQ(s.num_faces(), 3u);
  const int c = s.split_face(0, Eigen::Vector3d(0.2, 0.3, 0.5));
  EXPECT_EQ(s.num_faces(), 5u);
  EXPECT_EQ(s.maps().vertices[c].kind, VertexOriginKind::Interpolated);
  expect_tiles(m, s);

  // locate finds the soup face holding a point given in its original face's barycentrics.
  const FaceId parent(0);
  const Eigen::Vector3d b(0.3, 0.3, 0.4);
  Eigen::Vector3d local;
  const int f = s.locate(parent, b, local);
  ASSERT_GE(f, 0);
  const auto corners = m.face_vertices(parent);
  Vec3 want = Vec3::Zero(), got = Vec3::Zero();
  for (int j = 0; j < 3; ++j) want += b[j] * m.position(corners[j]);
  for (int k = 0; k < 3; ++k) got += local[k] * s.position(s.face(f)[k]);
  EXPECT_LT((want - got).norm(), 1e-12);
  EXPECT_EQ(s.locate(parent, Eigen::Vector3d(2.0, -0.5, -0.5), local), -1);  // outside

  // The rebuilt mesh has the soup's faces and hands over their maps.
  EditMaps maps;
  const SurfaceMesh built = std::move(s).build(maps);
  EXPECT_EQ(built.num_faces(), 5u);
  EXPECT_EQ(built.num_vertices(), 6u);
  EXPECT_EQ(maps.faces.size(), 5u);
  EXPECT_EQ(maps.vertices.size(), 6u);
  double total = 0.0;
  for (std::size_t f2 = 0; f2 < built.num_faces(); ++f2) total += built.face_area(FaceId(int(f2)));
  EXPECT_NEAR(total, 4.0, 1e-12);
}

}  // namespace
}  // namespace sutura::engine::detail
