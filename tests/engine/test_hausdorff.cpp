// Hausdorff distance between surfaces (measure/hausdorff.hpp) against closed forms.
#include "sutura/engine/measure/hausdorff.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

// Two 24-gon tubes of radius 4 and 4.1 with the same vertex angles. From the outer tube, the
// farthest points are its vertices, 0.1 mm from the inner tube's corners. From the inner tube,
// every point of a face lies 0.1 cos(pi/24) mm below the outer face parallel to it (a vertex
// sees the two outer faces beside the outer vertex at that distance, not the vertex itself).
TEST(Hausdorff, ConcentricTubesAreTheirRadialGapApart) {
  const SurfaceMesh inner = make_tube({4.0, 10.0, 24, 10}), outer = make_tube({4.1, 10.0, 24, 10});
  const HausdorffDistance h = hausdorff_distance(inner, outer, 0.1);
  const double gap = 0.1 * std::cos(M_PI / 24);
  EXPECT_NEAR(h.a_to_b, gap, 1e-9);
  EXPECT_NEAR(h.mean_a_to_b, gap, 1e-9);
  EXPECT_NEAR(h.b_to_a, 0.1, 1e-9);
  EXPECT_NEAR(h.symmetric, 0.1, 1e-9);
  EXPECT_GT(h.mean_b_to_a, gap - 1e-9);
  EXPECT_LT(h.mean_b_to_a, 0.1);
}

// A tube and its first half: the far rim of the whole tube is 10 mm from the half; every point
// of the half lies on the whole.
TEST(Hausdorff, OneSidedDistancesDifferForASubset) {
  const SurfaceMesh whole = make_tube({4.0, 20.0, 24, 20}), half = make_tube({4.0, 10.0, 24, 10});
  const HausdorffDistance h = hausdorff_distance(whole, half);
  EXPECT_NEAR(h.a_to_b, 10.0, 1e-9);
  EXPECT_NEAR(h.b_to_a, 0.0, 1e-12);
  EXPECT_EQ(h.symmetric, h.a_to_b);
  EXPECT_GT(h.samples_a, whole.num_vertices());
}

TEST(Hausdorff, IsSymmetricInItsArgumentsAndDeterministic) {
  const SurfaceMesh a = make_tube({4.0, 10.0, 24, 10}), b = make_strip({10.0, 4.0, 10, 4});
  const HausdorffDistance ab = hausdorff_distance(a, b), ba = hausdorff_distance(b, a);
  EXPECT_EQ(ab.a_to_b, ba.b_to_a);
  EXPECT_EQ(ab.b_to_a, ba.a_to_b);
  EXPECT_EQ(hausdorff_distance(a, b).symmetric, ab.symmetric);
}

TEST(Hausdorff, RefusesEmptyMeshesAndRunawaySampling) {
  const SurfaceMesh a = make_tube({4.0, 10.0, 24, 10});
  EXPECT_THROW(hausdorff_distance(a, SurfaceMesh()), InvalidArgument);
  EXPECT_THROW(hausdorff_distance(a, a, 1e-5), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
