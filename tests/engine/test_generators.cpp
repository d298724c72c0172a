// Procedural meshes: counts, boundaries, orientation, areas, spacing and parameter errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

constexpr double kPi = std::numbers::pi;

double edge_length(const SurfaceMesh& mesh, HalfedgeId h) {
  return (mesh.position(mesh.to_vertex(h)) - mesh.position(mesh.from_vertex(h))).norm();
}

// Smallest and largest interior angle over all faces, in degrees.
std::pair<double, double> angle_range(const SurfaceMesh& mesh) {
  double lo = 180.0, hi = 0.0;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto v = mesh.face_vertices(FaceId(f));
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = mesh.position(v[(k + 1) % 3]) - mesh.position(v[k]);
      const Vec3 b = mesh.position(v[(k + 2) % 3]) - mesh.position(v[k]);
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi;
      lo = std::min(lo, angle);
      hi = std::max(hi, angle);
    }
  }
  return {lo, hi};
}

// Every edge has one or two faces, boundary edges are exactly those of the loops, and no face
// is degenerate: an open, manifold, clean surface.
void expect_clean_open_surface(const SurfaceMesh& mesh, std::size_t expected_loops) {
  const ValidationReport report = mesh.validate();
  EXPECT_TRUE(report.ok()) << report.summary();
  const auto loops = mesh.boundary_loops();
  EXPECT_EQ(loops.size(), expected_loops);
  std::size_t loop_vertices = 0;
  for (const auto& loop : loops) loop_vertices += loop.size();
  std::size_t boundary_halfedges = 0;
  for (std::size_t h = 0; h < mesh.num_halfedges(); ++h) {
    if (mesh.is_boundary(HalfedgeId(h))) ++boundary_halfedges;
  }
  EXPECT_EQ(boundary_halfedges, loop_vertices);
  EXPECT_EQ(mesh.num_halfedges(), 2 * mesh.num_edges() - boundary_halfedges);
}

void expect_invalid_argument(const std::function<void()>& make, const std::string& name,
                             const std::string& value) {
  try {
    make();
    ADD_FAILURE() << "expected InvalidArgument for " << name;
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(name), std::string::npos) << message;
    EXPECT_NE(message.find(value), std::string::npos) << message;
  }
}

// --- tube --------------------------------------------------------------------------------------

TEST(Tube, CountsAndBoundaryLoops) {
  const TubeParams p{.radius = 3.0, .length = 12.0, .segments_around = 12, .segments_along = 5};
  const SurfaceMesh mesh = make_tube(p);
  EXPECT_EQ(mesh.num_vertices(), 12u * 6u);
  EXPECT_EQ(mesh.num_faces(), 2u * 12u * 5u);
  EXPECT_EQ(mesh.num_edges(), 3u * 12u * 5u + 12u);
  EXPECT_EQ(mesh.euler_characteristic(), 0);
  expect_clean_open_surface(mesh, 2);
  const auto loops = mesh.boundary_loops();
  ASSERT_EQ(loops.size(), 2u);
  for (const auto& loop : loops) EXPECT_EQ(loop.size(), 12u);
  // Bottom ring first (it holds vertex 0), at z = 0, running with increasing angle; the top
  // ring at z = length runs the other way (the mesh is on the left of both).
  EXPECT_EQ(loops[0][0].value, 0);
  EXPECT_EQ(loops[0][1].value, 1);
  EXPECT_EQ(loops[1][0].value, 60);
  EXPECT_EQ(loops[1][1].value, 71);
  for (VertexId v : loops[0]) EXPECT_DOUBLE_EQ(mesh.position(v).z(), 0.0);
  for (VertexId v : loops[1]) EXPECT_DOUBLE_EQ(mesh.position(v).z(), 12.0);
}

TEST(Tube, VerticesOnTheCylinderAndNormalsPointOutward) {
  const SurfaceMesh mesh =
      make_tube({.radius = 5.0, .length = 40.0, .segments_around = 32, .segments_along = 40});
  for (const Vec3& p : mesh.positions()) EXPECT_NEAR(std::hypot(p.x(), p.y()), 5.0, 1e-12);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 c = mesh.face_centroid(FaceId(f));
    const Vec3 radial(c.x(), c.y(), 0.0);
    EXPECT_GT(mesh.face_normal(FaceId(f)).dot(radial.normalized()), 0.99) << "face " << f;
  }
  const std::vector<Vec3> normals = mesh.vertex_normals();
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.position(VertexId(v));
    EXPECT_GT(normals[v].dot(Vec3(p.x(), p.y(), 0.0).normalized()), 0.99);
  }
}

TEST(Tube, AreaIsThatOfThePrism) {
  const SurfaceMesh mesh =
      make_tube({.radius = 2.0, .length = 7.0, .segments_around = 10, .segments_along = 3});
  const double side = 2.0 * 2.0 * std::sin(kPi / 10.0);
  EXPECT_NEAR(mesh.total_area(), 10.0 * side * 7.0, 1e-10);
}

TEST(Tube, DiagonalsAlternate) {
  const SurfaceMesh mesh =
      make_tube({.radius = 1.0, .length = 1.0, .segments_around = 4, .segments_along = 1});
  // Quad 0 (vertices 0,1,5,4) is split along 0-5, quad 1 (1,2,6,5) along 2-5.
  const auto has_edge = [&](std::int32_t a, std::int32_t b) {
    for (const FaceIndices& f : mesh.faces()) {
      for (int k = 0; k < 3; ++k) {
        if ((f[k] == a && f[(k + 1) % 3] == b) || (f[k] == b && f[(k + 1) % 3] == a)) return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(has_edge(0, 5));
  EXPECT_FALSE(has_edge(1, 4));
  EXPECT_TRUE(has_edge(2, 5));
  EXPECT_FALSE(has_edge(1, 6));
}

TEST(Tube, ParameterErrors) {
  expect_invalid_argument([] { make_tube({.radius = -1.0}); }, "radius", "-1");
  expect_invalid_argument([] { make_tube({.length = 0.0}); }, "length", "0");
  expect_invalid_argument([] { make_tube({.length = std::numeric_limits<double>::quiet_NaN()}); },
                          "length", "nan");
  expect_invalid_argument([] { make_tube({.segments_around = 2}); }, "segments_around", "2");
  expect_invalid_argument([] { make_tube({.segments_along = 0}); }, "segments_along", "0");
  expect_invalid_argument([] { make_tube({.segments_around = 100000, .segments_along = 100000}); },
                          "segments_around", "100000");
}

// --- strip -------------------------------------------------------------------------------------

TEST(CylinderPanel, CountsBoundaryAndOutwardNormals) {
  CylinderPanelParams p;
  p.radius = 25.0;
  p.length = 50.0;
  p.angle_start_deg = -40.0;
  p.angle_end_deg = 40.0;
  p.segments_around = 8;
  p.segments_along = 6;
  const SurfaceMesh m = make_cylinder_panel(p);
  EXPECT_TRUE(m.validate().ok()) << m.validate().summary();
  EXPECT_EQ(m.num_vertices(), 9u * 7u);
  EXPECT_EQ(m.num_faces(), 2u * 8u * 6u);
  const auto loops = m.boundary_loops();
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 2u * (8u + 6u));
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const Vec3 c = m.face_centroid(FaceId(f));
    const Vec3 radial(c.x(), 0.0, c.z());
    EXPECT_GT(m.face_normal(FaceId(f)).dot(radial.normalized()), 0.95) << "face " << f;
  }
  for (const Vec3& v : m.positions()) EXPECT_NEAR(std::hypot(v.x(), v.z()), 25.0, 1e-12);
  // The chord area of the facets approaches R * span * L from below.
  const double exact = 25.0 * (80.0 * std::numbers::pi / 180.0) * 50.0;
  EXPECT_LT(m.total_area(), exact);
  EXPECT_GT(m.total_area(), 0.99 * exact);
}

TEST(CylinderPanel, ParameterErrors) {
  CylinderPanelParams p;
  p.angle_end_deg = p.angle_start_deg;
  EXPECT_THROW(make_cylinder_panel(p), InvalidArgument);
  p = {};
  p.radius = -1.0;
  EXPECT_THROW(make_cylinder_panel(p), InvalidArgument);
  p = {};
  p.segments_along = 0;
  EXPECT_THROW(make_cylinder_panel(p), InvalidArgument);
}

TEST(Strip, CountsAreaAndOrientation) {
  const StripParams p{.length = 30.0, .width = 6.0, .segments_length = 15, .segments_width = 4};
  const SurfaceMesh mesh = make_strip(p);
  EXPECT_EQ(mesh.num_vertices(), 16u * 5u);
  EXPECT_EQ(mesh.num_faces(), 2u * 15u * 4u);
  EXPECT_EQ(mesh.euler_characteristic(), 1);
  expect_clean_open_surface(mesh, 1);
  EXPECT_EQ(mesh.boundary_loops()[0].size(), 2u * (15u + 4u));
  EXPECT_NEAR(mesh.total_area(), 30.0 * 6.0, 1e-10);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    EXPECT_TRUE(mesh.face_normal(FaceId(f)).isApprox(Vec3(0, 0, 1))) << "face " << f;
  }
  const Eigen::AlignedBox3d box = mesh.bounds();
  EXPECT_TRUE(box.min().isApprox(Vec3(0.0, -3.0, 0.0)));
  EXPECT_TRUE(box.max().isApprox(Vec3(30.0, 3.0, 0.0)));
}

TEST(Strip, DiagonalsAlternateLikeACheckerboard) {
  const SurfaceMesh mesh =
      make_strip({.length = 2.0, .width = 1.0, .segments_length = 2, .segments_width = 1});
  // Grid ids: bottom row 0 1 2, top row 3 4 5. Quad (0,1,4,3) split along 0-4, quad (1,2,5,4)
  // along 2-4.
  const std::vector<FaceIndices> expected = {{0, 1, 4}, {0, 4, 3}, {1, 2, 4}, {2, 5, 4}};
  EXPECT_EQ(mesh.faces(), expected);
}

TEST(Strip, ParameterErrors) {
  expect_invalid_argument([] { make_strip({.width = -2.5}); }, "width", "-2.5");
  expect_invalid_argument([] { make_strip({.length = std::numeric_limits<double>::infinity()}); },
                          "length", "inf");
  expect_invalid_argument([] { make_strip({.segments_length = 0}); }, "segments_length", "0");
  expect_invalid_argument([] { make_strip({.segments_width = -3}); }, "segments_width", "-3");
}

// --- patches -----------------------------------------------------------------------------------

struct PatchCase {
  PatchShape shape;
  double length, width, edge;
};

double analytic_area(const PatchCase& c) {
  return c.shape == PatchShape::Ellipse ? kPi * c.length * c.width / 4.0 : c.length * c.width / 2.0;
}

// Signed distance-like residual of a point from the shape's outline (0 on the outline).
double outline_residual(const PatchCase& c, const Vec3& p) {
  const double a = c.length / 2.0, b = c.width / 2.0;
  switch (c.shape) {
    case PatchShape::Ellipse:
      return std::hypot(p.x() / a, p.y() / b) - 1.0;
    case PatchShape::Diamond:
      return std::abs(p.x()) / a + std::abs(p.y()) / b - 1.0;
    case PatchShape::Triangle:
      // Base x = -a, sides |y| = b (a - x) / (2a).
      return std::min(std::abs(p.x() + a), std::abs(std::abs(p.y()) - b * (a - p.x()) / (2 * a)));
  }
  return 1.0;
}

class Patch : public ::testing::TestWithParam<PatchCase> {};

TEST_P(Patch, CleanDiskFacingUp) {
  const PatchCase c = GetParam();
  const SurfaceMesh mesh = make_patch({c.shape, c.length, c.width, c.edge});
  expect_clean_open_surface(mesh, 1);
  EXPECT_EQ(mesh.euler_characteristic(), 1);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    EXPECT_GT(mesh.face_normal(FaceId(f)).z(), 0.999) << "face " << f;
  }
  for (const Vec3& p : mesh.positions()) EXPECT_EQ(p.z(), 0.0);
}

TEST_P(Patch, AreaMatchesTheShape) {
  const PatchCase c = GetParam();
  const SurfaceMesh mesh = make_patch({c.shape, c.length, c.width, c.edge});
  EXPECT_NEAR(mesh.total_area() / analytic_area(c), 1.0, 0.02);
  const Eigen::AlignedBox3d box = mesh.bounds();
  EXPECT_NEAR(box.max().x() - box.min().x(), c.length, 1e-9);
  EXPECT_NEAR(box.max().y() - box.min().y(), c.width, 0.02 * c.width);
}

TEST_P(Patch, BoundaryFollowsTheOutlineAtTheTargetSpacing) {
  const PatchCase c = GetParam();
  const SurfaceMesh mesh = make_patch({c.shape, c.length, c.width, c.edge});
  const auto loop = mesh.boundary_loops().at(0);
  for (std::size_t k = 0; k < loop.size(); ++k) {
    EXPECT_NEAR(outline_residual(c, mesh.position(loop[k])), 0.0, 1e-9) << "boundary vertex " << k;
    const double spacing =
        (mesh.position(loop[(k + 1) % loop.size()]) - mesh.position(loop[k])).norm();
    EXPECT_GT(spacing, 0.5 * c.edge);
    EXPECT_LT(spacing, 1.5 * c.edge);
  }
}

TEST_P(Patch, EdgesNearTargetAndNoSlivers) {
  const PatchCase c = GetParam();
  const SurfaceMesh mesh = make_patch({c.shape, c.length, c.width, c.edge});
  EXPECT_NEAR(mesh.mean_edge_length() / c.edge, 1.0, 0.15);
  for (HalfedgeId h : mesh.edges()) EXPECT_LT(edge_length(mesh, h), 2.5 * c.edge);
  const auto [smallest, largest] = angle_range(mesh);
  EXPECT_GT(smallest, 15.0);
  EXPECT_LT(largest, 125.0);
}

TEST_P(Patch, Deterministic) {
  const PatchCase c = GetParam();
  const SurfaceMesh a = make_patch({c.shape, c.length, c.width, c.edge});
  const SurfaceMesh b = make_patch({c.shape, c.length, c.width, c.edge});
  EXPECT_EQ(a.faces(), b.faces());
  EXPECT_EQ(a.positions(), b.positions());
}

INSTANTIATE_TEST_SUITE_P(Shapes, Patch,
                         ::testing::Values(PatchCase{PatchShape::Ellipse, 20.0, 8.0, 1.0},
                                           PatchCase{PatchShape::Ellipse, 20.0, 8.0, 0.4},
                                           PatchCase{PatchShape::Ellipse, 10.0, 10.0, 0.5},
                                           PatchCase{PatchShape::Ellipse, 8.0, 20.0, 1.0},
                                           PatchCase{PatchShape::Ellipse, 40.0, 4.0, 0.5},
                                           PatchCase{PatchShape::Diamond, 20.0, 8.0, 1.0},
                                           PatchCase{PatchShape::Diamond, 20.0, 8.0, 0.4},
                                           PatchCase{PatchShape::Diamond, 12.0, 12.0, 0.75},
                                           PatchCase{PatchShape::Triangle, 20.0, 8.0, 1.0},
                                           PatchCase{PatchShape::Triangle, 20.0, 8.0, 0.4},
                                           PatchCase{PatchShape::Triangle, 10.0, 10.0, 0.5},
                                           PatchCase{PatchShape::Triangle, 8.0, 20.0, 1.0}));

TEST(PatchShapes, CornersAreVertices) {
  const SurfaceMesh diamond = make_patch({PatchShape::Diamond, 20.0, 8.0, 1.0});
  const SurfaceMesh triangle = make_patch({PatchShape::Triangle, 20.0, 8.0, 1.0});
  const auto has_vertex_at = [](const SurfaceMesh& mesh, const Vec3& p) {
    return std::any_of(mesh.positions().begin(), mesh.positions().end(),
                       [&](const Vec3& q) { return (q - p).norm() < 1e-9; });
  };
  for (const Vec3& corner : {Vec3(10, 0, 0), Vec3(0, 4, 0), Vec3(-10, 0, 0), Vec3(0, -4, 0)}) {
    EXPECT_TRUE(has_vertex_at(diamond, corner)) << corner.transpose();
  }
  for (const Vec3& corner : {Vec3(-10, -4, 0), Vec3(10, 0, 0), Vec3(-10, 4, 0)}) {
    EXPECT_TRUE(has_vertex_at(triangle, corner)) << corner.transpose();
  }
}

TEST(PatchShapes, NarrowPatchShrinksTheSpacingInsteadOfMakingFlatTriangles) {
  const SurfaceMesh mesh = make_patch({PatchShape::Ellipse, 20.0, 1.0, 2.0});
  expect_clean_open_surface(mesh, 1);
  EXPECT_LT(mesh.mean_edge_length(), 1.0);
  EXPECT_GT(angle_range(mesh).first, 20.0);
  EXPECT_NEAR(mesh.total_area() / (kPi * 20.0 * 1.0 / 4.0), 1.0, 0.02);
}

TEST(PatchShapes, CoarseSpacingStillGivesAValidPatch) {
  for (PatchShape shape : {PatchShape::Ellipse, PatchShape::Diamond, PatchShape::Triangle}) {
    const SurfaceMesh mesh = make_patch({shape, 3.0, 2.0, 50.0});
    expect_clean_open_surface(mesh, 1);
    EXPECT_GE(mesh.boundary_loops()[0].size(), 3u);
  }
}

TEST(PatchShapes, ParseNames) {
  EXPECT_EQ(parse_patch_shape("ellipse"), PatchShape::Ellipse);
  EXPECT_EQ(parse_patch_shape("diamond"), PatchShape::Diamond);
  EXPECT_EQ(parse_patch_shape("triangle"), PatchShape::Triangle);
  expect_invalid_argument([] { parse_patch_shape("hexagon"); }, "hexagon", "ellipse");
  EXPECT_THROW(parse_patch_shape("Ellipse"), InvalidArgument);
  EXPECT_THROW(parse_patch_shape(""), InvalidArgument);
}

TEST(PatchShapes, ParameterErrors) {
  expect_invalid_argument(
      [] {
        make_patch({PatchShape::Ellipse, -20.0, 8.0, 1.0});
      },
      "length", "-20");
  expect_invalid_argument([] { make_patch({PatchShape::Diamond, 20.0, 0.0, 1.0}); }, "width", "0");
  expect_invalid_argument(
      [] {
        make_patch({PatchShape::Triangle, 20.0, 8.0, 0.0});
      },
      "target_edge_length", "0");
  expect_invalid_argument(
      [] {
        make_patch({PatchShape::Ellipse, 20.0, 8.0, 1e-4});
      },
      "target_edge_length", "0.0001");
}

}  // namespace
}  // namespace sutura::engine
