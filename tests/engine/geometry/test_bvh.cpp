// Picking: the ray–triangle test against hand-computed hits, and the BVH against brute force.
#include <gtest/gtest.h>

#include <random>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/geometry/bvh.hpp"

using namespace sutura::engine;

namespace {

const Vec3 kA(0, 0, 0), kB(2, 0, 0), kC(0, 2, 0);

std::optional<RayHit> brute_force(const SurfaceMesh& mesh, const Ray& ray) {
  std::optional<RayHit> best;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto v = mesh.face_vertices(FaceId(f));
    auto hit = intersect_triangle(ray, mesh.position(v[0]), mesh.position(v[1]),
                                  mesh.position(v[2]));
    if (hit && (!best || hit->t < best->t)) {
      hit->face = FaceId(f);
      best = hit;
    }
  }
  return best;
}

}  // namespace

TEST(RayTriangle, HitsInteriorPointWithBarycentrics) {
  const auto hit = intersect_triangle({Vec3(0.5, 0.25, 3), Vec3(0, 0, -1)}, kA, kB, kC);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 3.0);
  EXPECT_DOUBLE_EQ(hit->u, 0.25);   // weight of corner B = x / 2
  EXPECT_DOUBLE_EQ(hit->v, 0.125);  // weight of corner C = y / 2
  EXPECT_TRUE(hit->point.isApprox(Vec3(0.5, 0.25, 0)));
}

TEST(RayTriangle, IsTwoSidedAndScalesTWithDirection) {
  const auto below = intersect_triangle({Vec3(0.5, 0.5, -2), Vec3(0, 0, 4)}, kA, kB, kC);
  ASSERT_TRUE(below);
  EXPECT_DOUBLE_EQ(below->t, 0.5);  // direction length 4: t counts in its units
}

TEST(RayTriangle, MissesOutsideBehindAndParallel) {
  EXPECT_FALSE(intersect_triangle({Vec3(1.5, 1.5, 1), Vec3(0, 0, -1)}, kA, kB, kC));  // outside
  EXPECT_FALSE(intersect_triangle({Vec3(0.5, 0.5, 1), Vec3(0, 0, 1)}, kA, kB, kC));   // behind
  EXPECT_FALSE(intersect_triangle({Vec3(0.5, 0.5, 0), Vec3(1, 0, 0)}, kA, kB, kC));   // in plane
  EXPECT_FALSE(intersect_triangle({Vec3(0.5, 0.5, 1), Vec3(0, 0, -1)}, kA, kB, kC, 0.0, 0.5));
}

TEST(RayTriangle, EdgesAndCornersCount) {
  EXPECT_TRUE(intersect_triangle({Vec3(1, 0, 1), Vec3(0, 0, -1)}, kA, kB, kC));  // on edge AB
  EXPECT_TRUE(intersect_triangle({Vec3(0, 2, 1), Vec3(0, 0, -1)}, kA, kB, kC));  // at corner C
}

TEST(TriangleBvh, FindsTheNearestOfTwoLayers) {
  StripParams p;
  SurfaceMesh strip = make_strip(p);  // z = 0
  std::vector<Vec3> pos = strip.positions();
  std::vector<FaceIndices> faces = strip.faces();
  const auto n = static_cast<std::int32_t>(pos.size());
  for (const auto& x : strip.positions()) pos.push_back(x + Vec3(0, 0, 5));
  for (auto f : strip.faces()) faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  const TriangleBvh bvh(pos, faces);
  const auto from_above = bvh.intersect({Vec3(10.3, 1.1, 20), Vec3(0, 0, -1)});
  ASSERT_TRUE(from_above);
  EXPECT_NEAR(from_above->point.z(), 5.0, 1e-12);
  EXPECT_GE(from_above->face.index(), strip.num_faces());
  const auto from_below = bvh.intersect({Vec3(10.3, 1.1, -20), Vec3(0, 0, 1)});
  ASSERT_TRUE(from_below);
  EXPECT_NEAR(from_below->point.z(), 0.0, 1e-12);
  EXPECT_FALSE(bvh.intersect({Vec3(10.3, 30, 20), Vec3(0, 0, -1)}));
}

TEST(TriangleBvh, AgreesWithBruteForceOnRandomRays) {
  TubeParams tp;
  tp.segments_around = 48;
  tp.segments_along = 30;
  const SurfaceMesh tube = make_tube(tp);
  const TriangleBvh bvh(tube);
  EXPECT_EQ(bvh.num_triangles(), tube.num_faces());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> box(-15.0, 55.0), dir(-1.0, 1.0);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    Ray ray{Vec3(box(rng) * 0.3, box(rng) * 0.3, box(rng)), Vec3(dir(rng), dir(rng), dir(rng))};
    if (i % 4 == 0) ray.direction = Vec3(1e-3 * dir(rng), 0, 0) + Vec3(0, 1, 0);  // near-axis rays
    const auto a = bvh.intersect(ray);
    const auto b = brute_force(tube, ray);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
    if (!a) continue;
    ++hits;
    EXPECT_DOUBLE_EQ(a->t, b->t) << "ray " << i;
    EXPECT_TRUE(a->point.isApprox(b->point, 1e-12)) << "ray " << i;
  }
  EXPECT_GT(hits, 200);  // the test exercises hits, not only misses
}

TEST(TriangleBvh, EmptyMeshNeverHits) {
  const TriangleBvh bvh({}, {});
  EXPECT_FALSE(bvh.intersect({Vec3::Zero(), Vec3::UnitX()}));
}

TEST(TriangleBvh, RejectsOutOfRangeFaces) {
  EXPECT_THROW(TriangleBvh({Vec3::Zero()}, {{0, 1, 2}}), InvalidArgument);
}
