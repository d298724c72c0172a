// carry: per-vertex and per-element data carried across an edit by its parent maps (pure
// functions: old data + maps in, new data out).
#include "sutura/engine/surgery/carry.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "surgery_fixture.hpp"

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/shell/rest_state.hpp"

namespace sutura::engine {
namespace {

using testing::vertex_origin;

// Old: 3 vertices, one face. New: the two old corners 0 and 1 copied, the midpoint of edge
// 1-2 (interpolated), corner 2 merged with corner 0 (a suture); face 0 untouched, face 1 the
// sub-face (0, 1, mid) of the old face, face 2 made by a remesh.
EditMaps maps() {
  EditMaps m;
  m.vertices = {vertex_origin(VertexOriginKind::Copy, {0}, {1.0}), vertex_origin(VertexOriginKind::Copy, {1}, {1.0}),
                vertex_origin(VertexOriginKind::Interpolated, {1, 2}, {0.5, 0.5}),
                vertex_origin(VertexOriginKind::Merged, {0, 2}, {0.5, 0.5})};
  FaceOrigin same;
  same.parent = FaceId(0);
  FaceOrigin sub = same;
  sub.bary << 1, 0, 0, 0, 1, 0, 0, 0.5, 0.5;
  FaceOrigin remeshed = sub;
  remeshed.kind = FaceOriginKind::Resampled;
  m.faces = {same, sub, remeshed};
  return m;
}

TEST(Carry, PointsAndStatesFollowTheWeights) {
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
  const std::vector<Vec3> p = carry_points(maps(), x);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0], x[0]);
  EXPECT_EQ(p[2], Vec3(1, 1, 0));
  EXPECT_EQ(p[3], Vec3(0, 1, 0));

  ShellState s;
  s.x = x;
  const Quat turned(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
  s.D = {Quat::Identity(), turned, Quat(-turned.coeffs())};  // -q: the same rotation as q
  const ShellState c = carry_state(maps(), s);
  EXPECT_EQ(c.x, p);
  EXPECT_EQ(c.D[1].coeffs(), turned.coeffs());  // one parent: copied bit for bit
  // Two parents with the same rotation (signs differ): the mean is that rotation, unit length.
  EXPECT_NEAR(std::abs(c.D[2].dot(turned)), 1.0, 1e-15);
  EXPECT_NEAR(c.D[2].norm(), 1.0, 1e-15);
  // Identity and a 0.4 rad turn: halfway, 0.2 rad about z.
  EXPECT_NEAR(c.D[3].angularDistance(Quat(Eigen::AngleAxisd(0.2, Vec3::UnitZ()))), 0.0, 1e-12);
}

TEST(Carry, RestShapesOfSubfacesFollowTheBarycentricsAndRemeshedOnesNeedTheGeometry) {
  ShellState s;
  s.x = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
  s.D.assign(3, Quat::Identity());
  RestState rest = rest_from_state(std::vector<FaceIndices>{{0, 1, 2}}, s);
  for (Vec3& X : rest.elements[0].X) X *= 1.1;  // a stressed parent: rest 10 % larger
  EditMaps m = maps();
  EXPECT_THROW(carry_rest(m, rest), InvalidArgument);  // the remeshed face needs its geometry
  m.faces.pop_back();
  const RestState c = carry_rest(m, rest);
  ASSERT_EQ(c.elements.size(), 2u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(c.elements[0].X[k], rest.elements[0].X[k]);  // untouched
  const auto& X = rest.elements[0].X;
  EXPECT_LT((c.elements[1].X[2] - 0.5 * (X[1] + X[2])).norm(), 1e-15);
  EXPECT_LT((c.elements[1].X[0] - X[0]).norm(), 1e-15);
}

TEST(Carry, FaceValuesConstraintsAndVerticesFollowTheirParents) {
  EXPECT_EQ(carry_face_values(maps(), {7}), (std::vector<int>{7, 7, 7}));
  EXPECT_EQ(carry_face_set(maps(), {FaceId(0)}), (std::vector<FaceId>{FaceId(0), FaceId(1), FaceId(2)}));
  EXPECT_TRUE(carry_face_set(maps(), {}).empty());

  Constraints old;
  old.fix({VertexId(1), VertexId(2)}, kAllDofs, 3);  // vertex 0 free
  old.fix({VertexId(0)}, kUz, 3);
  const Constraints c = carry_constraints(maps(), old);
  EXPECT_TRUE(c.is_fixed(1, 0));             // a copy keeps its DOFs
  EXPECT_TRUE(c.is_fixed(2, 4));             // between two fixed vertices: fixed
  EXPECT_TRUE(c.is_fixed(3, 0));             // sewn to a fixed vertex: fixed
  EXPECT_TRUE(c.is_fixed(0, 2));             // uz of vertex 0
  EXPECT_FALSE(c.is_fixed(0, 0));

  EditMaps between = maps();
  between.vertices[2] = vertex_origin(VertexOriginKind::Interpolated, {0, 1}, {0.5, 0.5});
  EXPECT_FALSE(carry_constraints(between, old).is_fixed(2, 0));  // fixed and free: free
  EXPECT_TRUE(carry_constraints(between, old).is_fixed(2, 2));   // uz fixed at both ends

  EXPECT_EQ(carry_vertex(maps(), VertexId(1)), VertexId(1));
  EXPECT_FALSE(carry_vertex(maps(), VertexId(2)).valid());  // merged (and interpolated from)
}

}  // namespace
}  // namespace sutura::engine
