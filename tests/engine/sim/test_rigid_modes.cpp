// free_rigid_motions: the rigid-body motions a body's fixed DOFs leave free, counted and named.
#include "sutura/engine/sim/rigid_modes.hpp"

#include <gtest/gtest.h>

#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

SurfaceMesh tube() { return make_tube({4.0, 30.0, 16, 12}); }

// Every free motion, applied to the nodes, moves no fixed DOF (to round-off).
void expect_restraints_kept(const std::vector<Vec3>& x, const Constraints& c,
                            const std::vector<RigidMotion>& free) {
  for (const RigidMotion& m : free)
    for (std::size_t v = 0; v < x.size(); ++v) {
      const Vec3 velocity = m.translation + m.rotation.cross(x[v] - m.point);
      for (int d = 0; d < 3; ++d) {
        if (c.is_fixed(v, d)) {
          EXPECT_NEAR(velocity(d), 0.0, 1e-9) << m.describe();
        }
      }
      for (int d = 3; d < 6; ++d) {
        if (c.is_fixed(v, d)) {
          EXPECT_NEAR(m.rotation(d - 3), 0.0, 1e-9) << m.describe();
        }
      }
    }
}

TEST(RigidModes, NothingFixedLeavesAllSixFree) {
  const SurfaceMesh m = tube();
  const auto free = free_rigid_motions(m.positions(), {});
  ASSERT_EQ(free.size(), 6u);
  int translations = 0;
  for (const auto& f : free) translations += f.rotation.norm() == 0.0;
  EXPECT_EQ(translations, 3);
}

TEST(RigidModes, HeldEndsRestrainEverything) {
  const SurfaceMesh m = tube();
  Constraints c;
  std::vector<VertexId> rims;
  for (const auto& loop : m.boundary_loops()) rims.insert(rims.end(), loop.begin(), loop.end());
  c.fix(rims, kTranslations, m.num_vertices());
  EXPECT_TRUE(free_rigid_motions(m.positions(), c).empty());
}

TEST(RigidModes, OneHeldNodeLeavesTheRotationsAboutIt) {
  const SurfaceMesh m = tube();
  Constraints c;
  const VertexId v(std::size_t(5));
  c.fix({v}, kTranslations, m.num_vertices());
  const auto free = free_rigid_motions(m.positions(), c);
  ASSERT_EQ(free.size(), 3u);
  for (const auto& f : free) {
    ASSERT_GT(f.rotation.norm(), 0.0);
    // The node lies on the axis.
    const Vec3 d = m.position(v) - f.point;
    EXPECT_NEAR((d - d.dot(f.rotation.normalized()) * f.rotation.normalized()).norm(), 0.0, 1e-9);
  }
  expect_restraints_kept(m.positions(), c, free);
  // Its rotations held too: nothing is free.
  c.fix({v}, kRotations, m.num_vertices());
  EXPECT_TRUE(free_rigid_motions(m.positions(), c).empty());
}

TEST(RigidModes, TwoHeldNodesLeaveTheRotationAboutTheirLine) {
  const SurfaceMesh m = tube();
  Constraints c;
  const VertexId a(std::size_t(0)), b(std::size_t(m.num_vertices() - 1));
  c.fix({a, b}, kTranslations, m.num_vertices());
  const auto free = free_rigid_motions(m.positions(), c);
  ASSERT_EQ(free.size(), 1u);
  const Vec3 line = (m.position(b) - m.position(a)).normalized();
  EXPECT_NEAR(std::abs(free[0].rotation.normalized().dot(line)), 1.0, 1e-9);
  expect_restraints_kept(m.positions(), c, free);
  EXPECT_NE(free[0].describe().find("rotation about the axis"), std::string::npos) << free[0].describe();
}

TEST(RigidModes, AFlatStripHeldOnlyAcrossItsPlaneSlidesAndTurnsInIt) {
  const SurfaceMesh m = make_strip({10.0, 4.0, 10, 4});  // in z = 0
  Constraints c;
  std::vector<VertexId> all;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) all.emplace_back(v);
  c.fix(all, kUz, m.num_vertices());
  const auto free = free_rigid_motions(m.positions(), c);
  ASSERT_EQ(free.size(), 3u);  // along x, along y, about z
  for (const auto& f : free) {
    EXPECT_NEAR(f.translation.z(), 0.0, 1e-9);
    EXPECT_NEAR(f.rotation.x(), 0.0, 1e-9);
    EXPECT_NEAR(f.rotation.y(), 0.0, 1e-9);
  }
  expect_restraints_kept(m.positions(), c, free);
}

}  // namespace
}  // namespace sutura::engine
