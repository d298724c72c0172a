#include "sutura/engine/surgery/incise.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "surgery_fixture.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {
namespace {

using testing::Body;

SurfaceMesh strip() { return make_strip({20.0, 10.0, 20, 10}); }

TEST(Incise, SnapSlitInsideStripMakesOneNewLoopWithSharedEnds) {
  const SurfaceMesh m = strip();
  const IncisionResult r =
      incise(m, {Vec3(5, 0, 0), Vec3(15, 0, 0)}, {IncisionMode::SnapToEdges});
  EXPECT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  EXPECT_EQ(r.mesh.boundary_loops().size(), 2u);
  ASSERT_EQ(r.left.size(), r.right.size());
  EXPECT_EQ(r.left.front(), r.right.front());  // slit ends are shared
  EXPECT_EQ(r.left.back(), r.right.back());
  EXPECT_FALSE(r.starts_on_boundary);
  EXPECT_FALSE(r.ends_on_boundary);
  EXPECT_EQ(r.inserted_vertices, 0);
  // 11 path vertices, the 9 interior ones duplicated.
  EXPECT_EQ(r.left.size(), 11u);
  EXPECT_EQ(r.mesh.num_vertices(), m.num_vertices() + 9);
  EXPECT_NEAR(r.length, 10.0, 1e-12);
  EXPECT_EQ(r.mesh.num_faces(), m.num_faces());
}

TEST(Incise, CutThroughFacesFollowsTheDrawnLineAndInsertsVertices) {
  const SurfaceMesh m = strip();
  // A diagonal that does not follow the mesh edges.
  const Vec3 a(4.3, -2.7, 0), b(15.6, 3.1, 0);
  const IncisionResult r = incise(m, {a, b});
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  EXPECT_GT(r.inserted_vertices, 5);
  const Vec3 d = (b - a).normalized();
  // Every cut vertex lies on the drawn segment, or (snapped by the sliver guard) within the
  // guard's fraction of the longest edge, the 1 mm cell's diagonal, from it.
  const double guard = IncisionParams{}.sliver_fraction * std::sqrt(2.0);
  for (const VertexId v : r.right) {
    const Vec3 p = r.mesh.position(v) - a;
    EXPECT_LT((p - p.dot(d) * d).norm(), guard + 1e-12);
  }
  EXPECT_NEAR(r.length, (b - a).norm(), 0.05 * (b - a).norm());
  // Area is preserved: the refinement only splits faces.
  EXPECT_NEAR(r.mesh.total_area(), m.total_area(), 1e-9);
}

TEST(Incise, MapsCarryARestStateThatLeavesTheCutMeshStressFree) {
  auto model = make_corotational_shell();
  Body body(make_tube({4.0, 20.0, 24, 20}));
  const IncisionResult r =
      incise(body.mesh, {Vec3(4, 0, 5.3), Vec3(0, 4, 12.7), Vec3(-4, 0.2, 15.1)});
  body.apply(r.mesh, r.maps);
  const auto [e, g] = testing::energy_and_force(*model, body);
  EXPECT_LT(e, 1e-20);
  EXPECT_LT(g, 1e-10);
}

TEST(Incise, FromTheBoundaryOpensTheLoop) {
  const SurfaceMesh tube = make_tube({4.0, 20.0, 24, 20});
  const IncisionResult r = incise(tube, {Vec3(4, 0, 0), Vec3(4, 0, 8.2)});
  ASSERT_TRUE(r.mesh.validate().ok());
  EXPECT_TRUE(r.starts_on_boundary);
  EXPECT_FALSE(r.ends_on_boundary);
  EXPECT_NE(r.left.front(), r.right.front());
  EXPECT_EQ(r.left.back(), r.right.back());
  EXPECT_EQ(r.mesh.boundary_loops().size(), 2u);  // the end loop grew by both lips
  std::size_t longest = 0;
  for (const auto& l : r.mesh.boundary_loops()) longest = std::max(longest, l.size());
  EXPECT_EQ(longest, 24u + 2 * (r.left.size() - 1));
}

TEST(Incise, EndToEndAlongATubeOpensItIntoASheet) {
  const SurfaceMesh tube = make_tube({4.0, 20.0, 24, 20});
  const IncisionResult r = incise(tube, {Vec3(4, 0, 0), Vec3(4, 0, 20)}, {IncisionMode::SnapToEdges});
  ASSERT_TRUE(r.mesh.validate().ok());
  EXPECT_EQ(r.mesh.boundary_loops().size(), 1u);
  EXPECT_EQ(r.mesh.euler_characteristic(), 1);  // a disc
}

TEST(Incise, RejectsBadRequestsWithClearMessages) {
  const SurfaceMesh m = strip();
  auto message = [&](const std::vector<Vec3>& pts, IncisionParams p = {}) {
    try {
      incise(m, pts, p);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({Vec3(5, 0, 0)}).find("at least 2 points"), std::string::npos);
  EXPECT_NE(message({Vec3(5, 0, 0), Vec3(15, 0, 3)}).find("off the surface"), std::string::npos);
  EXPECT_NE(message({Vec3(5, 0, 0), Vec3(5.1, 0, 0)}).find("shorter than one mesh edge"),
            std::string::npos);
  EXPECT_NE(message({Vec3(4, -3, 0), Vec3(12, 3, 0), Vec3(12, -3, 0), Vec3(4, 3, 0)}).find(
                "crosses itself"),
            std::string::npos);
  EXPECT_NE(message({Vec3(2, -2, 0), Vec3(10, 5, 0), Vec3(18, -2, 0)}).find("boundary"),
            std::string::npos);
  IncisionParams bad;
  bad.sliver_fraction = 0.7;
  EXPECT_NE(message({Vec3(5, 0, 0), Vec3(15, 0, 0)}, bad).find("sliver_fraction"),
            std::string::npos);
}

TEST(Incise, IsDeterministic) {
  const SurfaceMesh m = make_tube({4.0, 20.0, 24, 20});
  const std::vector<Vec3> pts{Vec3(4, 0, 5.3), Vec3(0, 4, 12.7)};
  const IncisionResult a = incise(m, pts), b = incise(m, pts);
  EXPECT_EQ(a.mesh.faces(), b.mesh.faces());
  EXPECT_EQ(a.mesh.positions(), b.mesh.positions());
}

}  // namespace
}  // namespace sutura::engine
