// edit_maps: the parent maps every edit returns, and their composition (compose), which
// carries data across several edits at once (an op that cuts, then remeshes).
#include "sutura/engine/surgery/edit_maps.hpp"

#include "sutura/engine/mesh.hpp"

#include <array>
#include <random>

#include <gtest/gtest.h>

#include "surgery_fixture.hpp"

namespace sutura::engine {
namespace {

using testing::vertex_origin;

// Three old vertices a, b, c -> a cut and a suture -> a split and a merge.
EditMaps first_edit() {
  EditMaps m;
  m.vertices = {vertex_origin(VertexOriginKind::Interpolated, {0, 1}, {0.25, 0.75}),  // v0 on edge ab
                vertex_origin(VertexOriginKind::Copy, {2}, {1.0}),                     // v1 = c
                vertex_origin(VertexOriginKind::Merged, {0, 1}, {0.5, 0.5})};          // v2 = a + b sewn
  FaceOrigin f;
  f.parent = FaceId(0);
  f.bary << 1, 0, 0, 0.5, 0.5, 0, 0, 0, 1;
  m.faces = {f};
  return m;
}

EditMaps second_edit() {
  EditMaps m;
  m.vertices = {vertex_origin(VertexOriginKind::Interpolated, {0, 1}, {0.5, 0.5}),  // w0 on v0 v1
                vertex_origin(VertexOriginKind::Merged, {1, 2}, {0.5, 0.5}),        // w1 = v1 + v2
                vertex_origin(VertexOriginKind::Copy, {0}, {1.0})};                 // w2 = v0
  FaceOrigin f;
  f.parent = FaceId(0);
  f.kind = FaceOriginKind::Resampled;
  f.bary << 0.2, 0.3, 0.5, 0, 1, 0, 0, 0, 1;
  m.faces = {f, f};
  m.faces[1].kind = FaceOriginKind::Subface;
  return m;
}

// Positions of the new vertices from the old ones, through one map.
std::vector<Vec3> positions_after(const EditMaps& m, const std::vector<Vec3>& x) {
  std::vector<Vec3> out;
  for (const VertexOrigin& o : m.vertices) {
    Vec3 p = Vec3::Zero();
    for (std::size_t i = 0; i < o.parents.size(); ++i) p += o.weights[i] * x[o.parents[i].index()];
    out.push_back(p);
  }
  return out;
}

TEST(EditMaps, IdentityIsNeutralOnBothSides) {
  const EditMaps m = first_edit();
  for (const EditMaps& c : {compose(EditMaps::identity(3, 1), m), compose(m, EditMaps::identity(3, 1))}) {
    ASSERT_EQ(c.vertices.size(), m.vertices.size());
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      EXPECT_EQ(c.vertices[v].kind, m.vertices[v].kind);
      EXPECT_EQ(c.vertices[v].parents, m.vertices[v].parents);
      EXPECT_EQ(c.vertices[v].weights, m.vertices[v].weights);
    }
    ASSERT_EQ(c.faces.size(), 1u);
    EXPECT_EQ(c.faces[0].parent, FaceId(0));
    EXPECT_EQ(c.faces[0].bary, m.faces[0].bary);
    EXPECT_EQ(c.faces[0].kind, m.faces[0].kind);
  }
}

TEST(EditMaps, ComposedVerticesExpandTheWeightsAndKeepTheStrongestKind) {
  const EditMaps c = compose(first_edit(), second_edit());
  ASSERT_EQ(c.vertices.size(), 3u);
  // w0 = (v0 + v1) / 2 = 0.125 a + 0.375 b + 0.5 c, a point inside the old face.
  EXPECT_EQ(c.vertices[0].kind, VertexOriginKind::Interpolated);
  EXPECT_EQ(c.vertices[0].parents, (std::vector<VertexId>{VertexId(0), VertexId(1), VertexId(2)}));
  EXPECT_EQ(c.vertices[0].weights, (std::vector<double>{0.125, 0.375, 0.5}));
  // w1 = (c + (a + b) / 2) / 2: a merge stays a merge (a suture's vertex is sewn for good).
  EXPECT_EQ(c.vertices[1].kind, VertexOriginKind::Merged);
  EXPECT_EQ(c.vertices[1].weights, (std::vector<double>{0.25, 0.25, 0.5}));
  // w2, a copy of an interpolated vertex, is interpolated.
  EXPECT_EQ(c.vertices[2].kind, VertexOriginKind::Interpolated);
  EXPECT_EQ(c.vertices[2].weights, (std::vector<double>{0.25, 0.75}));
  for (const VertexOrigin& o : c.vertices) {
    double sum = 0.0;
    for (double w : o.weights) sum += w;
    EXPECT_DOUBLE_EQ(sum, 1.0);
  }
}

TEST(EditMaps, ComposedFacesMultiplyTheBarycentricsAndKeepTheStrongestKind) {
  const EditMaps a = first_edit(), b = second_edit();
  const EditMaps c = compose(a, b);
  ASSERT_EQ(c.faces.size(), 2u);
  for (const FaceOrigin& f : c.faces) {
    EXPECT_EQ(f.parent, FaceId(0));
    EXPECT_TRUE(f.bary.isApprox(b.faces[0].bary * a.faces[0].bary, 0.0));
    EXPECT_TRUE(f.bary.rowwise().sum().isApproxToConstant(1.0, 1e-15));
  }
  EXPECT_EQ(c.faces[0].kind, FaceOriginKind::Resampled);
  EXPECT_EQ(c.faces[1].kind, FaceOriginKind::Subface);
}

// Carrying positions through the composed map is the same as through one map after the other.
TEST(EditMaps, ComposingCarriesPositionsAsTheTwoEditsInTurn) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  std::vector<Vec3> x;
  for (int i = 0; i < 3; ++i) x.emplace_back(u(rng), u(rng), u(rng));
  const EditMaps a = first_edit(), b = second_edit();
  const std::vector<Vec3> in_turn = positions_after(b, positions_after(a, x));
  const std::vector<Vec3> at_once = positions_after(compose(a, b), x);
  ASSERT_EQ(in_turn.size(), at_once.size());
  for (std::size_t v = 0; v < in_turn.size(); ++v) EXPECT_LT((in_turn[v] - at_once[v]).norm(), 1e-13);
}

}  // namespace
}  // namespace sutura::engine
