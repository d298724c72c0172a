// segmentation_like: the synthetic segmentation export is closed, dense, noisy within its
// bound, and the same on every run.
#include <gtest/gtest.h>

#include "sutura/engine/anatomy/segmentation_export.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

TEST(SegmentationLike, ClosesSubdividesAndStaysWithinTheNoise) {
  TubeParams t;
  t.radius = 3.0;
  t.length = 10.0;
  t.segments_around = 24;
  t.segments_along = 10;
  const SurfaceMesh tube = make_tube(t);
  SegmentationLikeParams p;
  p.max_edge_length = 0.3;
  p.noise = 0.05;
  const SurfaceMesh m = segmentation_like(tube, p);
  EXPECT_TRUE(m.boundary_loops().empty());
  EXPECT_EQ(m.euler_characteristic(), 2);
  EXPECT_LE(m.mean_edge_length(), 0.3);
  EXPECT_TRUE(m.validate().ok()) << m.validate().summary();
  // Without noise the same mesh; every vertex then moved by at most the noise, and some by a
  // good part of it.
  p.noise = 0.0;
  const SurfaceMesh clean = segmentation_like(tube, p);
  ASSERT_EQ(clean.num_vertices(), m.num_vertices());
  double largest = 0.0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    largest = std::max(largest, (m.positions()[v] - clean.positions()[v]).norm());
  EXPECT_LE(largest, 0.05 + 1e-12);
  EXPECT_GT(largest, 0.04);
  // Deterministic, and the seed matters.
  p.noise = 0.05;
  EXPECT_EQ(segmentation_like(tube, p).positions(), m.positions());
  p.seed = 2;
  EXPECT_NE(segmentation_like(tube, p).positions(), m.positions());
}

TEST(SegmentationLike, RefusesBadParameters) {
  const SurfaceMesh tube = make_tube(TubeParams{});
  SegmentationLikeParams p;
  p.max_edge_length = 0.0;
  EXPECT_THROW(segmentation_like(tube, p), InvalidArgument);
  p = {};
  p.noise = -1.0;
  EXPECT_THROW(segmentation_like(tube, p), InvalidArgument);
  p = {};
  p.max_edge_length = 0.001;
  p.max_faces = 100'000;
  EXPECT_THROW(segmentation_like(tube, p), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
