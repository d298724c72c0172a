// Harmonic extension and as-rigid-as-possible deformation (the join's OntoB placement).
#include "shape_deformation.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

// Strip 10 x 4 mm along x, its two short edges prescribed.
struct Strip {
  SurfaceMesh mesh = make_strip({10.0, 4.0, 10, 4});
  std::vector<bool> ends;
  Strip() {
    ends.assign(mesh.num_vertices(), false);
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
      const double x = mesh.position(VertexId(v)).x();
      ends[v] = std::abs(x) < 1e-12 || std::abs(x - 10.0) < 1e-12;
    }
  }
};

TEST(ShapeDeformation, HarmonicSpreadStaysWithinThePrescribedValues) {
  // One end held, the other moved 1 mm along x: every free displacement is a convex
  // combination of its neighbours' (positive weights), so it lies in [0, 1] along x and has
  // no other component; it grows from the held end to the moved one.
  Strip s;
  std::vector<Vec3> value(s.mesh.num_vertices(), Vec3::Zero());
  for (std::size_t v = 0; v < value.size(); ++v)
    if (s.mesh.position(VertexId(v)).x() > 5.0) value[v] = Vec3(1, 0, 0);
  const auto d = detail::harmonic_spread(s.mesh.positions(), s.mesh.faces(), s.ends, value);
  for (std::size_t v = 0; v < d.size(); ++v) {
    const Vec3 x = s.mesh.position(VertexId(v));
    if (s.ends[v]) {
      EXPECT_EQ(d[v], value[v]);
      continue;
    }
    EXPECT_GT(d[v].x(), 0.0);
    EXPECT_LT(d[v].x(), 1.0);
    EXPECT_NEAR(d[v].y(), 0.0, 1e-12);
    EXPECT_NEAR(d[v].z(), 0.0, 1e-12);
    EXPECT_NEAR(d[v].x(), x.x() / 10.0, 0.1) << "roughly linear along the strip";
  }
}

TEST(ShapeDeformation, AsRigidAsPossibleReproducesARotationTheHarmonicSpreadShrinks) {
  // Both ends turned by 150 degrees about the strip's centre line (z axis through (5, 0)):
  // the rigid fit moves every vertex onto the rotated strip, while the linear interpolation
  // of the ends' displacements pulls the middle towards the axis.
  Strip s;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(5.0 * M_PI / 6.0, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 c(5, 0, 0);
  std::vector<Vec3> value(s.mesh.num_vertices(), Vec3::Zero());
  for (std::size_t v = 0; v < value.size(); ++v) {
    const Vec3 x = s.mesh.position(VertexId(v));
    if (s.ends[v]) value[v] = c + R * (x - c) - x;
  }
  const auto p = detail::as_rigid_as_possible(s.mesh.positions(), s.mesh.faces(), s.ends, value, 20, 8);
  const auto d = detail::harmonic_spread(s.mesh.positions(), s.mesh.faces(), s.ends, value);
  double worst_rigid = 0.0, worst_harmonic = 0.0;
  for (std::size_t v = 0; v < p.size(); ++v) {
    const Vec3 x = s.mesh.position(VertexId(v));
    const Vec3 expected = c + R * (x - c);
    worst_rigid = std::max(worst_rigid, (p[v] - expected).norm());
    worst_harmonic = std::max(worst_harmonic, (x + d[v] - expected).norm());
  }
  EXPECT_LT(worst_rigid, 1e-3);
  // In one stage the same iteration folds the strip through itself and stays there.
  const auto folded =
      detail::as_rigid_as_possible(s.mesh.positions(), s.mesh.faces(), s.ends, value, 160, 1);
  double worst_folded = 0.0;
  for (std::size_t v = 0; v < p.size(); ++v) {
    const Vec3 x = s.mesh.position(VertexId(v));
    worst_folded = std::max(worst_folded, (folded[v] - (c + R * (x - c))).norm());
  }
  EXPECT_GT(worst_folded, 0.5);
  EXPECT_GT(worst_harmonic, 0.5);
}

TEST(ShapeDeformation, PartsWithoutAPrescribedVertexStayAndBadSizesAreRejected) {
  Strip s;
  std::vector<bool> none(s.mesh.num_vertices(), false);
  std::vector<Vec3> value(s.mesh.num_vertices(), Vec3(1, 2, 3));
  const auto d = detail::harmonic_spread(s.mesh.positions(), s.mesh.faces(), none, value);
  for (const Vec3& x : d) EXPECT_EQ(x, Vec3::Zero());
  const auto p = detail::as_rigid_as_possible(s.mesh.positions(), s.mesh.faces(), none, value, 5, 2);
  EXPECT_EQ(p, s.mesh.positions());
  EXPECT_THROW(detail::harmonic_spread(s.mesh.positions(), s.mesh.faces(), {true}, value),
               InvalidArgument);
  EXPECT_THROW(detail::as_rigid_as_possible(s.mesh.positions(), s.mesh.faces(), none, {}, 5, 1),
               InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
