#include "sutura/engine/surgery/resect.hpp"

#include <gtest/gtest.h>

#include "surgery_fixture.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/surgery/join.hpp"

namespace sutura::engine {
namespace {

using testing::Body;

SurfaceMesh tube() { return make_tube({3.0, 30.0, 24, 30}); }

TEST(Resect, BandBetweenTwoPlanesLeavesTwoCleanLoops) {
  const SurfaceMesh m = tube();
  const ResectionResult r =
      resect(m, {{Vec3(0, 0, 10.5), Vec3(0, 0, 1)}, {Vec3(0, 0, 15.5), Vec3(0, 0, -1)}},
             Vec3(0, 0, 13));
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  ASSERT_EQ(r.loops.size(), 2u);
  EXPECT_EQ(r.mesh.boundary_loops().size(), 4u);  // two tube ends and two cut loops
  for (const auto& loop : r.loops) {
    EXPECT_TRUE(loop.closed);
    EXPECT_EQ(loop.vertices.size(), 48u);  // each quad is crossed on its generator and its diagonal
  }
  for (const VertexId v : r.loops[0].vertices) EXPECT_NEAR(r.mesh.position(v).z(), 10.5, 1e-12);
  for (const VertexId v : r.loops[1].vertices) EXPECT_NEAR(r.mesh.position(v).z(), 15.5, 1e-12);
  // The band between the planes (5 mm of the tube) is gone.
  EXPECT_NEAR(r.removed_area, 2.0 * 3.0 * 24 * std::sin(M_PI / 24) * 5.0, 1e-9);
  EXPECT_NEAR(r.mesh.total_area() + r.removed_area, m.total_area(), 1e-9);
}

TEST(Resect, MapsCarryAStressFreeRestState) {
  auto model = make_corotational_shell();
  Body body(tube());
  const ResectionResult r = resect(
      body.mesh, {{Vec3(0, 0, 10.3), Vec3(0, 0.3, 1)}, {Vec3(0, 0, 15.7), Vec3(0.2, 0, -1)}},
      Vec3(0, 0, 13));
  body.apply(r.mesh, r.maps);
  const auto [e, g] = testing::energy_and_force(*model, body);
  EXPECT_LT(e, 1e-20);
  EXPECT_LT(g, 1e-10);
}

TEST(Resect, EndToEndAnastomosisClosesTheGap) {
  const SurfaceMesh m = tube();
  const ResectionResult r =
      resect(m, {{Vec3(0, 0, 10.5), Vec3(0, 0, 1)}, {Vec3(0, 0, 15.5), Vec3(0, 0, -1)}},
             Vec3(0, 0, 13));
  const JoinResult j = join(r.mesh, {{r.loops[0], r.loops[1]}});
  ASSERT_TRUE(j.mesh.validate().ok()) << j.mesh.validate().summary();
  EXPECT_EQ(j.mesh.boundary_loops().size(), 2u);
  EXPECT_EQ(j.merged.size(), 48u);
  for (const VertexId v : j.merged) EXPECT_NEAR(j.mesh.position(v).z(), 13.0, 1e-12);
}

TEST(Resect, OnePlaneDividesAndRemovesTheFarPart) {
  const SurfaceMesh m = tube();
  const ResectionResult r = resect(m, {{Vec3(0, 0, 20.5), Vec3(0, 0, 1)}}, Vec3(0, 0, 28));
  ASSERT_TRUE(r.mesh.validate().ok());
  EXPECT_NEAR(r.mesh.bounds().max().z(), 20.5, 1e-12);
  EXPECT_EQ(r.loops.size(), 1u);
}

TEST(Resect, ReportsACutThatDoesNotGoAllTheWayRound) {
  const SurfaceMesh m = tube();
  try {
    resect(m, {{Vec3(0, 0, 10.5), Vec3(0, 0, 1)}, {Vec3(3, 0, 15.5), Vec3(0, 0, -1)}},
           Vec3(3, 0, 13), {1.5, 0.15});
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("all the way round"), std::string::npos) << e.what();
  }
  EXPECT_THROW(resect(m, {}, Vec3::Zero()), InvalidArgument);
  // A seed far off the surface (../shared/robustness/wrong_success_resect_seed_outside.jsonl)
  // is refused, naming its distance; one inside the lumen (3 mm from the wall) is not.
  try {
    resect(m, {{Vec3(0, 0, 15), Vec3(0, 0, 1)}}, Vec3(400, 0, 20));
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("the seed (400, 0, 20) lies 397"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(resect(m, {{Vec3(0, 0, 15), Vec3(0, 0, 1)}}, Vec3(0, 0, 20)));
  EXPECT_THROW(resect(m, {{Vec3::Zero(), Vec3::Zero()}}, Vec3::Zero()), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
