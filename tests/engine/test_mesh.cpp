// SurfaceMesh: construction, corner-table adjacency, fans, boundary loops, geometry helpers,
// validate() and every TopologyError the constructor raises.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/mesh.hpp"

namespace sutura::engine {
namespace {

SurfaceMesh single_triangle() {
  return SurfaceMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}});
}

// Unit square in z = 0 split along 0-2.
SurfaceMesh unit_square() {
  return SurfaceMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)},
                     {{0, 1, 2}, {0, 2, 3}});
}

// Closed tetrahedron with outward-facing triangles.
SurfaceMesh tetrahedron() {
  return SurfaceMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                     {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

SurfaceMesh small_tube() {
  return make_tube({.radius = 2.0, .length = 6.0, .segments_around = 8, .segments_along = 3});
}

std::vector<std::int32_t> values(const std::vector<VertexId>& ids) {
  std::vector<std::int32_t> out;
  for (VertexId v : ids) out.push_back(v.value);
  return out;
}

std::vector<std::int32_t> values(const std::vector<FaceId>& ids) {
  std::vector<std::int32_t> out;
  for (FaceId f : ids) out.push_back(f.value);
  return out;
}

// Checks every adjacency invariant against the face array with brute force, independently of
// validate().
void expect_consistent_adjacency(const SurfaceMesh& mesh) {
  for (std::size_t i = 0; i < mesh.num_halfedges(); ++i) {
    const HalfedgeId h(i);
    EXPECT_EQ(SurfaceMesh::face(h).index(), i / 3);
    EXPECT_EQ(SurfaceMesh::next(SurfaceMesh::next(SurfaceMesh::next(h))), h);
    EXPECT_EQ(SurfaceMesh::prev(SurfaceMesh::next(h)), h);
    EXPECT_EQ(mesh.to_vertex(h), mesh.from_vertex(SurfaceMesh::next(h)));
    if (mesh.is_boundary(h)) continue;
    const HalfedgeId t = mesh.twin(h);
    EXPECT_EQ(mesh.twin(t), h) << "twin symmetry at half-edge " << i;
    EXPECT_EQ(mesh.from_vertex(t), mesh.to_vertex(h));
    EXPECT_EQ(mesh.to_vertex(t), mesh.from_vertex(h));
    EXPECT_NE(SurfaceMesh::face(t), SurfaceMesh::face(h));
  }
  for (std::size_t i = 0; i < mesh.num_vertices(); ++i) {
    const VertexId v(i);
    EXPECT_EQ(mesh.from_vertex(mesh.vertex_halfedge(v)), v);
    std::set<std::int32_t> expected;
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
      for (std::int32_t u : mesh.faces()[f]) {
        if (u == v.value) expected.insert(static_cast<std::int32_t>(f));
      }
    }
    const std::vector<FaceId> fan = mesh.vertex_faces(v);
    const std::vector<std::int32_t> fan_values = values(fan);
    EXPECT_EQ(std::set<std::int32_t>(fan_values.begin(), fan_values.end()), expected)
        << "fan of vertex " << i;
    EXPECT_EQ(fan.size(), expected.size()) << "fan of vertex " << i << " repeats a face";
    const std::size_t neighbours = mesh.vertex_neighbors(v).size();
    EXPECT_EQ(neighbours, fan.size() + (mesh.is_boundary(v) ? 1 : 0));
  }
}

// Consecutive neighbours (n_k, n_k+1) of v close the triangle (v, n_k, n_k+1) with the mesh's
// orientation: the fan runs counter-clockwise seen from the normal side.
void expect_counter_clockwise_fan(const SurfaceMesh& mesh, VertexId v) {
  const std::vector<VertexId> ring = mesh.vertex_neighbors(v);
  const std::vector<FaceId> fan = mesh.vertex_faces(v);
  const std::size_t pairs = mesh.is_boundary(v) ? ring.size() - 1 : ring.size();
  ASSERT_EQ(pairs, fan.size());
  for (std::size_t k = 0; k < pairs; ++k) {
    const FaceIndices expected = {v.value, ring[k].value, ring[(k + 1) % ring.size()].value};
    FaceIndices face = mesh.faces()[fan[k].index()];
    while (face[0] != v.value) std::rotate(face.begin(), face.begin() + 1, face.end());
    EXPECT_EQ(face, expected) << "vertex " << v << ", fan position " << k;
  }
}

void expect_topology_error(std::vector<Vec3> positions, std::vector<FaceIndices> faces,
                           const std::string& phrase) {
  try {
    SurfaceMesh mesh(std::move(positions), std::move(faces));
    ADD_FAILURE() << "expected a TopologyError containing \"" << phrase << "\"";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos)
        << "message \"" << e.what() << "\" lacks \"" << phrase << "\"";
  }
}

TEST(SurfaceMesh, DefaultIsEmptyAndValid) {
  const SurfaceMesh mesh;
  EXPECT_TRUE(mesh.empty());
  EXPECT_EQ(mesh.num_vertices(), 0u);
  EXPECT_EQ(mesh.num_edges(), 0u);
  EXPECT_TRUE(mesh.boundary_loops().empty());
  EXPECT_EQ(mesh.mean_edge_length(), 0.0);
  EXPECT_TRUE(mesh.validate().ok());
}

TEST(SurfaceMesh, SingleTriangle) {
  const SurfaceMesh mesh = single_triangle();
  EXPECT_EQ(mesh.num_vertices(), 3u);
  EXPECT_EQ(mesh.num_faces(), 1u);
  EXPECT_EQ(mesh.num_halfedges(), 3u);
  EXPECT_EQ(mesh.num_edges(), 3u);
  EXPECT_FALSE(mesh.empty());
  for (int k = 0; k < 3; ++k) {
    const HalfedgeId h = SurfaceMesh::halfedge(FaceId(0), k);
    EXPECT_EQ(h.value, k);
    EXPECT_TRUE(mesh.is_boundary(h));
    EXPECT_FALSE(mesh.twin(h).valid());
    EXPECT_EQ(mesh.from_vertex(h).value, k);
    EXPECT_EQ(mesh.to_vertex(h).value, (k + 1) % 3);
    EXPECT_EQ(SurfaceMesh::next(h).value, (k + 1) % 3);
    EXPECT_EQ(SurfaceMesh::prev(h).value, (k + 2) % 3);
    EXPECT_TRUE(mesh.is_boundary(VertexId(k)));
  }
  EXPECT_EQ(mesh.face_vertices(FaceId(0)), (std::array{VertexId(0), VertexId(1), VertexId(2)}));
  EXPECT_EQ(values(mesh.vertex_faces(VertexId(0))), (std::vector<std::int32_t>{0}));
  EXPECT_EQ(values(mesh.vertex_neighbors(VertexId(0))), (std::vector<std::int32_t>{1, 2}));
  ASSERT_EQ(mesh.boundary_loops().size(), 1u);
  EXPECT_EQ(values(mesh.boundary_loops()[0]), (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(mesh.euler_characteristic(), 1);
  EXPECT_DOUBLE_EQ(mesh.face_area(FaceId(0)), 0.5);
  EXPECT_TRUE(mesh.face_normal(FaceId(0)).isApprox(Vec3(0, 0, 1)));
  EXPECT_TRUE(mesh.validate().ok()) << mesh.validate().summary();
  expect_consistent_adjacency(mesh);
}

TEST(SurfaceMesh, TwoTrianglesShareOneEdge) {
  const SurfaceMesh mesh = unit_square();
  EXPECT_EQ(mesh.num_edges(), 5u);
  // Half-edge 0->2 of face 0 is corner 2 (2->0), twin of corner 0 of face 1 (0->2).
  const HalfedgeId shared = SurfaceMesh::halfedge(FaceId(0), 2);
  ASSERT_FALSE(mesh.is_boundary(shared));
  EXPECT_EQ(mesh.twin(shared), SurfaceMesh::halfedge(FaceId(1), 0));
  EXPECT_EQ(mesh.twin(mesh.twin(shared)), shared);
  EXPECT_EQ(mesh.edges().size(), 5u);
  ASSERT_EQ(mesh.boundary_loops().size(), 1u);
  EXPECT_EQ(values(mesh.boundary_loops()[0]), (std::vector<std::int32_t>{0, 1, 2, 3}));
  EXPECT_EQ(mesh.euler_characteristic(), 1);
  expect_consistent_adjacency(mesh);
}

TEST(SurfaceMesh, BoundaryVertexFansRunCounterClockwiseFromTheBoundaryHalfedge) {
  const SurfaceMesh mesh = unit_square();
  // Vertex 0 at the origin: neighbours (1,0), (1,1), (0,1) by increasing angle.
  EXPECT_TRUE(mesh.is_boundary(mesh.vertex_halfedge(VertexId(0))));
  EXPECT_EQ(values(mesh.vertex_faces(VertexId(0))), (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(values(mesh.vertex_neighbors(VertexId(0))), (std::vector<std::int32_t>{1, 2, 3}));
  // Vertex 2 at (1,1): (0,1), (0,0), (1,0).
  EXPECT_EQ(values(mesh.vertex_faces(VertexId(2))), (std::vector<std::int32_t>{1, 0}));
  EXPECT_EQ(values(mesh.vertex_neighbors(VertexId(2))), (std::vector<std::int32_t>{3, 0, 1}));
  for (std::size_t v = 0; v < 4; ++v) expect_counter_clockwise_fan(mesh, VertexId(v));
}

TEST(SurfaceMesh, ClosedTetrahedron) {
  const SurfaceMesh mesh = tetrahedron();
  EXPECT_EQ(mesh.num_edges(), 6u);
  EXPECT_TRUE(mesh.boundary_loops().empty());
  EXPECT_EQ(mesh.euler_characteristic(), 2);
  for (std::size_t h = 0; h < mesh.num_halfedges(); ++h)
    EXPECT_FALSE(mesh.is_boundary(HalfedgeId(h)));
  const Vec3 centre(0.25, 0.25, 0.25);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_FALSE(mesh.is_boundary(VertexId(v)));
    EXPECT_EQ(mesh.vertex_faces(VertexId(v)).size(), 3u);
    EXPECT_EQ(mesh.vertex_neighbors(VertexId(v)).size(), 3u);
    expect_counter_clockwise_fan(mesh, VertexId(v));
    EXPECT_GT(mesh.vertex_normals()[v].dot(mesh.position(VertexId(v)) - centre), 0.0);
  }
  for (std::size_t f = 0; f < 4; ++f) {
    EXPECT_GT(mesh.face_normal(FaceId(f)).dot(mesh.face_centroid(FaceId(f)) - centre), 0.0);
  }
  EXPECT_NEAR(mesh.total_area(), 1.5 + std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_TRUE(mesh.validate().ok()) << mesh.validate().summary();
  expect_consistent_adjacency(mesh);
}

TEST(SurfaceMesh, GeneratedTube) {
  const SurfaceMesh mesh = small_tube();
  EXPECT_EQ(mesh.num_vertices(), 8u * 4u);
  EXPECT_EQ(mesh.num_faces(), 2u * 8u * 3u);
  EXPECT_EQ(mesh.euler_characteristic(), 0);
  EXPECT_EQ(mesh.boundary_loops().size(), 2u);
  std::size_t boundary_vertices = 0;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.is_boundary(VertexId(v))) ++boundary_vertices;
    expect_counter_clockwise_fan(mesh, VertexId(v));
  }
  EXPECT_EQ(boundary_vertices, 16u);
  // Sum of valences counts every edge twice.
  std::size_t valence_sum = 0;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    valence_sum += mesh.vertex_neighbors(VertexId(v)).size();
  }
  EXPECT_EQ(valence_sum, 2 * mesh.num_edges());
  EXPECT_TRUE(mesh.validate().ok()) << mesh.validate().summary();
  expect_consistent_adjacency(mesh);
}

TEST(SurfaceMesh, EdgesListEachUndirectedEdgeOnceInHalfedgeOrder) {
  const SurfaceMesh mesh = small_tube();
  const std::vector<HalfedgeId> edges = mesh.edges();
  EXPECT_EQ(edges.size(), mesh.num_edges());
  EXPECT_TRUE(std::is_sorted(edges.begin(), edges.end()));
  std::set<std::pair<std::int32_t, std::int32_t>> seen;
  for (HalfedgeId h : edges) {
    EXPECT_TRUE(mesh.is_boundary(h) || h < mesh.twin(h));
    const std::int32_t a = mesh.from_vertex(h).value, b = mesh.to_vertex(h).value;
    EXPECT_TRUE(seen.insert({std::min(a, b), std::max(a, b)}).second);
  }
}

TEST(SurfaceMesh, BoundaryLoopsStartAtTheirSmallestVertexAndAreSortedByIt) {
  // The tube with its vertex ids reversed: loops must still start at their smallest id and
  // follow the boundary half-edges (mesh on the left).
  const SurfaceMesh tube = small_tube();
  const auto n = static_cast<std::int32_t>(tube.num_vertices());
  std::vector<Vec3> positions(tube.positions().rbegin(), tube.positions().rend());
  std::vector<FaceIndices> faces;
  for (FaceIndices f : tube.faces()) faces.push_back({n - 1 - f[0], n - 1 - f[1], n - 1 - f[2]});
  const SurfaceMesh mesh(std::move(positions), std::move(faces));

  const auto loops = mesh.boundary_loops();
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_LT(loops[0][0], loops[1][0]);
  for (const auto& loop : loops) {
    EXPECT_EQ(loop.size(), 8u);
    EXPECT_EQ(*std::min_element(loop.begin(), loop.end()), loop.front());
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const HalfedgeId h = mesh.vertex_halfedge(loop[k]);
      EXPECT_TRUE(mesh.is_boundary(h));
      EXPECT_EQ(mesh.to_vertex(h), loop[(k + 1) % loop.size()]);
    }
  }
  // The reversed ids put the top ring (z = length) first: ids 0..7.
  EXPECT_EQ(loops[0][0].value, 0);
  EXPECT_DOUBLE_EQ(mesh.position(loops[0][0]).z(), 6.0);
}

TEST(SurfaceMesh, GeometryHelpers) {
  const SurfaceMesh mesh = unit_square();
  EXPECT_DOUBLE_EQ(mesh.total_area(), 1.0);
  EXPECT_TRUE(mesh.face_centroid(FaceId(0)).isApprox(Vec3(2.0 / 3.0, 1.0 / 3.0, 0.0)));
  EXPECT_NEAR(mesh.mean_edge_length(), (4.0 + std::sqrt(2.0)) / 5.0, 1e-15);
  for (const Vec3& n : mesh.vertex_normals()) EXPECT_TRUE(n.isApprox(Vec3(0, 0, 1)));
  const Eigen::AlignedBox3d box = mesh.bounds();
  EXPECT_TRUE(box.min().isApprox(Vec3(0, 0, 0)));
  EXPECT_TRUE(box.max().isApprox(Vec3(1, 1, 0)));
  EXPECT_TRUE(mesh.degenerate_faces().empty());
}

TEST(SurfaceMesh, DegenerateFacesAreFoundAndReported) {
  SurfaceMesh mesh = unit_square();
  mesh.set_position(VertexId(3), Vec3(0.5, 0.5, 0.0));  // on the diagonal: face 1 collapses
  EXPECT_EQ(values(mesh.degenerate_faces()), (std::vector<std::int32_t>{1}));
  EXPECT_TRUE(mesh.face_normal(FaceId(1)).isZero());
  const ValidationReport report = mesh.validate();
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.summary().find("face 1 is degenerate"), std::string::npos) << report.summary();
}

TEST(SurfaceMesh, ValidateReportsEveryNonFinitePosition) {
  SurfaceMesh mesh = tetrahedron();
  mesh.set_position(VertexId(1), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  mesh.set_position(VertexId(3), Vec3(0, 0, std::numeric_limits<double>::infinity()));
  const ValidationReport report = mesh.validate();
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.summary().find("vertex 1 has a non-finite coordinate"), std::string::npos);
  EXPECT_NE(report.summary().find("vertex 3 has a non-finite coordinate"), std::string::npos);
  EXPECT_NE(report.summary().find("; "), std::string::npos);
}

TEST(SurfaceMesh, SetPositionsReplacesAllOrThrows) {
  SurfaceMesh mesh = single_triangle();
  mesh.set_positions({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)});
  EXPECT_DOUBLE_EQ(mesh.total_area(), 2.0);
  EXPECT_THROW(mesh.set_positions({Vec3(0, 0, 0)}), InvalidArgument);
}

TEST(SurfaceMesh, FlatArraysForTheRenderer) {
  const SurfaceMesh mesh = tetrahedron();
  const std::vector<float> xyz = mesh.flat_positions();
  ASSERT_EQ(xyz.size(), 12u);
  EXPECT_EQ(xyz[9], 0.0f);
  EXPECT_EQ(xyz[11], 1.0f);
  const std::vector<std::uint32_t> tris = mesh.flat_triangles();
  ASSERT_EQ(tris.size(), 12u);
  EXPECT_EQ((std::vector<std::uint32_t>(tris.begin() + 9, tris.end())),
            (std::vector<std::uint32_t>{1, 2, 3}));
}

TEST(SurfaceMesh, ConstructionIsDeterministic) {
  const SurfaceMesh a = small_tube();
  const SurfaceMesh b = small_tube();
  for (std::size_t v = 0; v < a.num_vertices(); ++v) {
    EXPECT_EQ(a.vertex_halfedge(VertexId(v)), b.vertex_halfedge(VertexId(v)));
  }
  for (std::size_t h = 0; h < a.num_halfedges(); ++h) {
    EXPECT_EQ(a.twin(HalfedgeId(h)), b.twin(HalfedgeId(h)));
  }
}

// --- TopologyError cases -----------------------------------------------------------------------

const std::vector<Vec3> kFivePoints = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0),
                                       Vec3(-1, 0, 0)};

TEST(SurfaceMeshErrors, IndexOutOfRange) {
  expect_topology_error({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 5}}, "out of range");
  expect_topology_error({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, -1, 2}},
                        "references vertex -1");
}

TEST(SurfaceMeshErrors, RepeatedVertexInFace) {
  expect_topology_error({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 1}},
                        "face 0 repeats vertex 1");
}

TEST(SurfaceMeshErrors, EdgeWithThreeFaces) {
  expect_topology_error(kFivePoints, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}, "shared by 3 faces");
}

TEST(SurfaceMeshErrors, InconsistentOrientation) {
  expect_topology_error(kFivePoints, {{0, 1, 2}, {0, 1, 3}}, "inconsistent orientation");
}

TEST(SurfaceMeshErrors, BowTieVertexIsPinched) {
  // Two triangles touching only at vertex 0.
  expect_topology_error(
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)},
      {{0, 1, 2}, {0, 3, 4}}, "vertex 0 is pinched");
}

TEST(SurfaceMeshErrors, TwoClosedFansAtOneVertexArePinched) {
  // Two tetrahedra sharing only vertex 0: both fans are closed, no boundary anywhere.
  std::vector<Vec3> positions = {Vec3(0, 0, 0),  Vec3(1, 0, 0),  Vec3(0, 1, 0), Vec3(0, 0, 1),
                                 Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)};
  std::vector<FaceIndices> faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
                                    {0, 5, 4}, {0, 4, 6}, {0, 6, 5}, {4, 5, 6}};
  expect_topology_error(positions, faces, "2 separate fans");
}

TEST(SurfaceMeshErrors, UnusedVertex) {
  expect_topology_error({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 5, 5)}, {{0, 1, 2}},
                        "vertex 3 is not used");
}

TEST(SurfaceMeshErrors, NonFiniteCoordinate) {
  expect_topology_error(
      {Vec3(0, 0, 0), Vec3(1, std::numeric_limits<double>::infinity(), 0), Vec3(0, 1, 0)},
      {{0, 1, 2}}, "vertex 1 has a non-finite coordinate");
}

TEST(SurfaceMeshErrors, TopologyErrorIsAnEngineError) {
  EXPECT_THROW(SurfaceMesh({Vec3(0, 0, 0)}, {{0, 0, 0}}), Error);
}

}  // namespace
}  // namespace sutura::engine
