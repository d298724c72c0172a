// prepare_vessel: cap detection, quality, distance to the input, determinism, and the errors of
// bad segmentation exports. Inputs are generated (segmentation_like), never stored files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "sutura/engine/anatomy/segmentation_export.hpp"
#include "sutura/engine/compute_threads.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/measure/centreline.hpp"
#include "sutura/engine/patient/prepare.hpp"
#include "tree_distance.hpp"

namespace sutura::engine {
namespace {

double min_angle(const SurfaceMesh& m) {
  double lo = 180.0;
  for (const FaceIndices& f : m.faces())
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = m.positions()[f[k]];
      const Vec3 a = m.positions()[f[(k + 1) % 3]] - p, b = m.positions()[f[(k + 2) % 3]] - p;
      lo = std::min(lo, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi);
    }
  return lo;
}

SurfaceMesh capped_tube(double noise = 0.02) {
  TubeParams t;
  t.radius = 3.0;
  t.length = 20.0;
  t.segments_around = 48;
  t.segments_along = 80;
  SegmentationLikeParams s;
  s.max_edge_length = 0.3;
  s.noise = noise;
  return segmentation_like(make_tube(t), s);
}

// The fine arch: a segmentation export resolves curvature far below a millimetre (the coarse
// arch's facets would be creases the prepared surface has to follow).
const ArchAnatomy& arch() {
  static const ArchAnatomy a = [] {
    ArchParams p;
    p.target_edge_length = kArchFineEdgeLength;
    return generate_arch(p);
  }();
  return a;
}

const SurfaceMesh& capped_arch() {
  static const SurfaceMesh m = segmentation_like(arch().aorta, SegmentationLikeParams{});
  return m;
}

const PrepareResult& prepared_arch() {
  static const PrepareResult r = prepare_vessel(capped_arch());
  return r;
}

TEST(Prepare, CappedTubeOpensBothCapsAndNothingElse) {
  const SurfaceMesh input = capped_tube();
  ASSERT_TRUE(input.boundary_loops().empty());
  const PrepareResult r = prepare_vessel(input);
  ASSERT_EQ(r.ends.size(), 2u);
  EXPECT_EQ(r.vessel.boundary_loops().size(), 2u);
  EXPECT_EQ(r.vessel.euler_characteristic(), 0);  // an open tube: an annulus
  for (const PreparedEnd& e : r.ends) {
    EXPECT_TRUE(e.was_cap);
    EXPECT_NEAR(e.end.radius, 3.0, 0.03);
    EXPECT_NEAR(std::abs(e.end.normal.z()), 1.0, 1e-3);
    // Outward: the end at z = 0 looks down, the one at z = 20 up.
    EXPECT_GT(e.end.normal.z() * (e.end.centre.z() - 10.0), 0.0);
    EXPECT_NEAR(std::abs(e.end.centre.z() - 10.0), 10.0, 0.03);
  }
  EXPECT_TRUE(r.vessel.validate().ok()) << r.vessel.validate().summary();
}

TEST(Prepare, InwardOrientedInputIsTurnedOutward) {
  const SurfaceMesh input = capped_tube();
  std::vector<FaceIndices> faces = input.faces();
  for (FaceIndices& f : faces) std::swap(f[1], f[2]);
  const PrepareResult r = prepare_vessel(SurfaceMesh(input.positions(), faces));
  EXPECT_TRUE(r.flipped);
  // Outward: vertex normals point away from the axis.
  const auto normals = r.vessel.vertex_normals();
  for (std::size_t v = 0; v < normals.size(); ++v) {
    const Vec3 radial(r.vessel.positions()[v].x(), r.vessel.positions()[v].y(), 0.0);
    ASSERT_GT(normals[v].dot(radial), 0.0) << "vertex " << v;
  }
}

TEST(Prepare, KeepCapsReportsTheCapsAndKeepsThemClosed) {
  PrepareParams p;
  p.keep_caps = true;
  const PrepareResult r = prepare_vessel(capped_tube(), p);
  EXPECT_EQ(r.ends.size(), 2u);
  EXPECT_TRUE(r.vessel.boundary_loops().empty());
  EXPECT_EQ(r.vessel.euler_characteristic(), 2);
}

TEST(Prepare, CappedArchFindsEveryEnd) {
  const PrepareResult& r = prepared_arch();
  const auto& truth = arch().landmarks.aorta_ends;
  ASSERT_EQ(r.ends.size(), truth.size());
  EXPECT_EQ(r.vessel.boundary_loops().size(), truth.size());
  EXPECT_EQ(r.vessel.euler_characteristic(), 2 - static_cast<int>(truth.size()));
  for (const VesselEnd& t : truth) {
    const PreparedEnd* found = nullptr;
    for (const PreparedEnd& e : r.ends)
      if (!found || (e.end.centre - t.centre).norm() < (found->end.centre - t.centre).norm()) found = &e;
    ASSERT_NE(found, nullptr);
    EXPECT_LT((found->end.centre - t.centre).norm(), 0.05) << t.name;
    EXPECT_NEAR(found->end.radius, t.radius, 0.02 * t.radius) << t.name;
    EXPECT_GT(found->end.normal.dot(t.normal), std::cos(2.0 * std::numbers::pi / 180.0)) << t.name;
  }
  // Named by decreasing radius.
  for (std::size_t i = 0; i < r.ends.size(); ++i) {
    EXPECT_EQ(r.ends[i].end.name, "end_" + std::to_string(i + 1));
    if (i > 0) {
      EXPECT_LE(r.ends[i].end.radius, r.ends[i - 1].end.radius);
    }
  }
}

// The automatic centreline of the prepared export (the ends as prepare found them) follows the
// arch's analytic aortic centreline: within a tenth of the lumen radius away from the branch
// junctions (3 aortic radii around each branch's origin), and its narrowest point is the
// coarctation.
TEST(Prepare, CentrelineOfThePreparedArch) {
  const PrepareResult& r = prepared_arch();
  std::vector<VesselEnd> ends;
  for (const PreparedEnd& e : r.ends) ends.push_back(e.end);
  const CentrelineTree t = extract_centreline(r.vessel, ends);
  EXPECT_EQ(t.branch_points.size(), 3u);
  const Centreline* aorta = nullptr;
  std::vector<Vec3> origins;
  for (const Centreline& c : arch().landmarks.centrelines) {
    if (c.name == "aorta") aorta = &c;
    else if (c.name.find("pulmonary") == std::string::npos) origins.push_back(c.points.front());
  }
  ASSERT_NE(aorta, nullptr);
  double worst = 0.0;
  for (std::size_t i = 0; i < aorta->points.size(); ++i) {
    bool near_branch = false;
    for (const Vec3& o : origins) near_branch |= (aorta->points[i] - o).norm() < 3.0 * aorta->radii[i];
    if (!near_branch) worst = std::max(worst, distance_to_tree(t, aorta->points[i]) / aorta->radii[i]);
  }
  EXPECT_LT(worst, 0.1);
  int narrowest = -1;
  for (std::size_t v = 0; v < t.points.size(); ++v)
    if ((t.points[v] - arch().landmarks.coarctation_centre).norm() < 5.0 &&
        (narrowest < 0 || t.radii[v] < t.radii[static_cast<std::size_t>(narrowest)]))
      narrowest = static_cast<int>(v);
  ASSERT_GE(narrowest, 0);
  EXPECT_LT((t.points[static_cast<std::size_t>(narrowest)] - arch().landmarks.coarctation_centre).norm(), 1.0);
  EXPECT_NEAR(t.radii[static_cast<std::size_t>(narrowest)], arch().landmarks.coarctation_min_radius,
              0.1 * arch().landmarks.coarctation_min_radius);
}

TEST(Prepare, RemeshedArchIsWellShaped) {
  const PrepareResult& r = prepared_arch();
  EXPECT_GE(r.min_angle_deg, 25.0);
  EXPECT_DOUBLE_EQ(r.min_angle_deg, min_angle(r.vessel));
  EXPECT_TRUE(r.vessel.validate().ok()) << r.vessel.validate().summary();
  // The default target: 16 edges around the narrowest end.
  const double r_min = r.ends.back().end.radius;
  EXPECT_NEAR(r.edge_length, 2.0 * std::numbers::pi * r_min / 16.0, 0.02 * r.edge_length);
  // Finer where the wall bends faster than the target can follow (the coarctation, the narrow
  // branches), never below a fifth of it; most edges near the target.
  std::vector<double> lengths;
  for (const HalfedgeId e : r.vessel.edges())
    lengths.push_back((r.vessel.position(r.vessel.to_vertex(e)) - r.vessel.position(r.vessel.from_vertex(e))).norm());
  std::sort(lengths.begin(), lengths.end());
  EXPECT_GT(lengths[lengths.size() / 2], 0.7 * r.edge_length);
  EXPECT_LT(lengths[lengths.size() / 2], 1.1 * r.edge_length);
  EXPECT_GT(lengths.front(), 0.2 * r.edge_length);
  EXPECT_DOUBLE_EQ(r.min_edge, lengths.front());
}

TEST(Prepare, RemeshedArchStaysOnTheSegmentation) {
  const PrepareResult& r = prepared_arch();
  EXPECT_LT(r.to_input.a_to_b, 0.1 * r.edge_length);
  EXPECT_LT(r.to_input.b_to_a, 0.1 * r.edge_length);
  EXPECT_LT(r.to_input.mean_a_to_b, 0.02 * r.edge_length);
}

TEST(Prepare, IsDeterministic) {
  const SurfaceMesh input = capped_tube();
  const PrepareResult a = prepare_vessel(input), b = prepare_vessel(input);
  ASSERT_EQ(a.vessel.num_vertices(), b.vessel.num_vertices());
  EXPECT_EQ(a.vessel.faces(), b.vessel.faces());
  for (std::size_t v = 0; v < a.vessel.num_vertices(); ++v)
    ASSERT_EQ(a.vessel.positions()[v], b.vessel.positions()[v]) << "vertex " << v;
}

// A large export's first coarsening runs in two halves of the surface, joined again along their
// cut (on two threads when allowed); the threshold is lowered here so that small inputs take
// that path.
TEST(Prepare, CoarseningInHalvesIsTheSameOnAnyThreadCount) {
  const SurfaceMesh input = capped_tube();
  PrepareParams params;
  params.coarsen_in_halves_from = 1000;
  const int threads = compute_threads().openmp;
  set_compute_threads(1);
  const PrepareResult one = prepare_vessel(input, params);
  set_compute_threads(2);
  const PrepareResult two = prepare_vessel(input, params);
  set_compute_threads(threads);
  EXPECT_TRUE(two.vessel.validate().ok()) << two.vessel.validate().summary();
  EXPECT_EQ(two.vessel.boundary_loops().size(), 2u);
  EXPECT_GE(two.min_angle_deg, 25.0);
  EXPECT_LT(two.to_input.symmetric, 0.1 * two.edge_length);
  ASSERT_EQ(one.vessel.num_vertices(), two.vessel.num_vertices());
  EXPECT_EQ(one.vessel.faces(), two.vessel.faces());
  for (std::size_t v = 0; v < one.vessel.num_vertices(); ++v)
    ASSERT_EQ(one.vessel.positions()[v], two.vessel.positions()[v]) << "vertex " << v;
  // The halves are a different path from the one pass (which the default takes here).
  EXPECT_NE(prepare_vessel(input).vessel.positions(), two.vessel.positions());
}

TEST(Prepare, ArchCoarsenedInHalvesIsWellShapedAndStaysOnTheSegmentation) {
  PrepareParams params;
  params.coarsen_in_halves_from = 1000;
  const PrepareResult r = prepare_vessel(capped_arch(), params);
  EXPECT_TRUE(r.vessel.validate().ok()) << r.vessel.validate().summary();
  EXPECT_EQ(r.ends.size(), prepared_arch().ends.size());
  EXPECT_EQ(r.vessel.boundary_loops().size(), prepared_arch().vessel.boundary_loops().size());
  EXPECT_GE(r.min_angle_deg, 25.0);
  EXPECT_LT(r.to_input.a_to_b, 0.1 * r.edge_length);
  EXPECT_LT(r.to_input.b_to_a, 0.1 * r.edge_length);
  EXPECT_LT(r.to_input.mean_a_to_b, 0.02 * r.edge_length);
}

TEST(Prepare, SmallComponentsAreDroppedAndReported) {
  const SurfaceMesh tube = capped_tube();
  SegmentationLikeParams s;
  s.max_edge_length = 0.3;
  TubeParams small;
  small.radius = 0.5;
  small.length = 1.0;
  small.segments_around = 8;
  small.segments_along = 2;
  const SurfaceMesh speck = segmentation_like(make_tube(small), s);
  std::vector<Vec3> x = tube.positions();
  std::vector<FaceIndices> f = tube.faces();
  const int offset = static_cast<int>(x.size());
  for (const Vec3& p : speck.positions()) x.push_back(p + Vec3(10.0, 0.0, 0.0));
  for (const FaceIndices& t : speck.faces()) f.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const PrepareResult r = prepare_vessel(SurfaceMesh(x, f));
  ASSERT_EQ(r.dropped.size(), 1u);
  EXPECT_EQ(r.dropped[0].faces, speck.num_faces());
  EXPECT_NEAR(r.dropped[0].centroid.x(), 10.0, 0.1);
  EXPECT_EQ(r.ends.size(), 2u);
}

TEST(PrepareErrors, SeveralLargeComponentsAreRefused) {
  const SurfaceMesh tube = capped_tube();
  std::vector<Vec3> x = tube.positions();
  std::vector<FaceIndices> f = tube.faces();
  const int offset = static_cast<int>(x.size());
  for (const Vec3& p : tube.positions()) x.push_back(p + Vec3(10.0, 0.0, 0.0));
  for (const FaceIndices& t : tube.faces()) f.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  try {
    prepare_vessel(SurfaceMesh(x, f));
    FAIL() << "two tubes were prepared";
  } catch (const PrepareError& e) {
    EXPECT_EQ(e.kind(), PrepareError::Kind::SeveralComponents);
    EXPECT_NE(std::string(e.what()).find("several large components"), std::string::npos) << e.what();
  }
}

TEST(PrepareErrors, AHoleInTheWallIsRefused) {
  // Faces removed from the middle of a capped tube's wall leave a hole that is no vessel end.
  const SurfaceMesh tube = capped_tube(0.0);
  std::vector<FaceIndices> kept;
  for (std::size_t f = 0; f < tube.num_faces(); ++f) {
    const Vec3 c = tube.face_centroid(FaceId(static_cast<int>(f)));
    if (!(c.x() > 2.5 && std::abs(c.z() - 10.0) < 1.0 && std::abs(c.y()) < 1.0)) kept.push_back(tube.faces()[f]);
  }
  ASSERT_LT(kept.size(), tube.num_faces());
  // The vertices inside the hole go with their faces.
  std::vector<int> index(tube.num_vertices(), -1);
  std::vector<Vec3> x;
  for (FaceIndices& t : kept)
    for (int& v : t) {
      if (index[static_cast<std::size_t>(v)] < 0) {
        index[static_cast<std::size_t>(v)] = static_cast<int>(x.size());
        x.push_back(tube.positions()[static_cast<std::size_t>(v)]);
      }
      v = index[static_cast<std::size_t>(v)];
    }
  const SurfaceMesh holed(x, kept);
  try {
    prepare_vessel(holed);
    FAIL() << "a hole in the wall was taken for an end";
  } catch (const PrepareError& e) {
    EXPECT_EQ(e.kind(), PrepareError::Kind::OpenHole);
    EXPECT_NE(std::string(e.what()).find("hole"), std::string::npos) << e.what();
  }
}

TEST(PrepareErrors, ANonFlatHoleIsRefused) {
  // An open tube end cut along a saddle (z varies around the rim by 1.5 mm).
  TubeParams t;
  t.radius = 3.0;
  t.length = 20.0;
  t.segments_around = 48;
  t.segments_along = 40;
  SurfaceMesh tube = make_tube(t);
  std::vector<Vec3> x = tube.positions();
  for (Vec3& p : x) p.z() += 1.5 * std::pow(p.z() / 20.0, 4) * std::cos(2.0 * std::atan2(p.y(), p.x()));
  try {
    prepare_vessel(SurfaceMesh(x, tube.faces()));
    FAIL() << "a saddle-shaped end was accepted";
  } catch (const PrepareError& e) {
    EXPECT_EQ(e.kind(), PrepareError::Kind::OpenHole);
    EXPECT_NE(std::string(e.what()).find("not a flat open end"), std::string::npos) << e.what();
  }
}

TEST(PrepareErrors, SelfIntersectionsAreReported) {
  SurfaceMesh tube = capped_tube(0.0);
  // One wall vertex pushed through the opposite wall.
  std::size_t v = 0;
  for (; v < tube.num_vertices(); ++v) {
    const Vec3& p = tube.positions()[v];
    if (p.x() > 2.99 && std::abs(p.z() - 10.0) < 0.2) break;
  }
  ASSERT_LT(v, tube.num_vertices());
  std::vector<Vec3> x = tube.positions();
  x[v].x() = -4.0;
  try {
    prepare_vessel(SurfaceMesh(x, tube.faces()));
    FAIL() << "a self-intersecting surface was prepared";
  } catch (const PrepareError& e) {
    EXPECT_EQ(e.kind(), PrepareError::Kind::SelfIntersecting);
    EXPECT_NE(std::string(e.what()).find("intersects itself"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(self_intersections(SurfaceMesh(x, tube.faces()), 0).empty());
  EXPECT_TRUE(self_intersections(tube, 0).empty());
}

TEST(PrepareErrors, EdgeLengthOutOfRangeIsRefused) {
  for (const double h : {0.05, 5.0, -1.0}) {
    PrepareParams p;
    p.edge_length = h;
    try {
      prepare_vessel(capped_tube(), p);
      FAIL() << "edge length " << h << " was accepted";
    } catch (const PrepareError& e) {
      EXPECT_EQ(e.kind(), PrepareError::Kind::EdgeLength) << e.what();
    }
  }
}

TEST(PrepareErrors, AClosedSurfaceWithoutCapsIsRefused) {
  // A sphere-like closed surface: no flat caps, no open ends.
  const SurfaceMesh input = segmentation_like(make_tube(TubeParams{}), SegmentationLikeParams{1.0, 0.0, 1});
  std::vector<Vec3> x = input.positions();
  for (Vec3& p : x) p = 10.0 * (p - Vec3(0, 0, 20)).normalized();
  try {
    prepare_vessel(SurfaceMesh(x, input.faces()));
    FAIL() << "a sphere was prepared";
  } catch (const PrepareError& e) {
    EXPECT_EQ(e.kind(), PrepareError::Kind::NoEnds) << e.what();
  }
}

// A clip plane across the descending aorta, 10 mm above its capped end: the vessel ends
// there in a flat open end of the aorta's radius, and what was removed is the 10 mm of tube
// and the cap (2 pi r L + pi r^2).
TEST(Prepare, AClipPlaneEndsTheVesselThere) {
  const VesselEnd& descending = arch().landmarks.aorta_ends[1];
  ASSERT_EQ(descending.name, "descending");
  PrepareParams p;
  PrepareClip clip;
  clip.origin = descending.centre - 10.0 * descending.normal;
  clip.normal = descending.normal;
  clip.radius = 8.0;
  p.clips.push_back(clip);
  const PrepareResult r = prepare_vessel(capped_arch(), p);
  ASSERT_EQ(r.ends.size(), 5u);
  const PreparedEnd* at_clip = nullptr;
  for (const PreparedEnd& e : r.ends)
    if ((e.end.centre - clip.origin).norm() < 0.1) at_clip = &e;
  ASSERT_NE(at_clip, nullptr);
  EXPECT_FALSE(at_clip->was_cap);
  EXPECT_NEAR(at_clip->end.radius, descending.radius, 0.02 * descending.radius);
  EXPECT_GT(at_clip->end.normal.dot(descending.normal), std::cos(2.0 * std::numbers::pi / 180.0));
  ASSERT_EQ(r.clipped.size(), 1u);
  const double removed = 2.0 * std::numbers::pi * descending.radius * 10.0 + std::numbers::pi * descending.radius * descending.radius;
  EXPECT_NEAR(r.clipped[0].second, removed, 0.02 * removed);
  EXPECT_GE(r.min_angle_deg, 25.0);
}

TEST(PrepareErrors, AClipPlaneThatCutsNothingIsRefused) {
  for (const Vec3& normal : {Vec3(0, 0, 1), Vec3(0, 0, 0)}) {
    PrepareParams p;
    p.clips.push_back({Vec3(0, 0, 100), normal, 5.0});
    try {
      prepare_vessel(capped_tube(), p);
      FAIL() << "a clip plane far from the surface was accepted";
    } catch (const PrepareError& e) {
      EXPECT_EQ(e.kind(), PrepareError::Kind::Clip) << e.what();
      EXPECT_NE(std::string(e.what()).find("clip plane 1"), std::string::npos) << e.what();
    }
  }
}

TEST(PrepareErrors, TooManyFacesAreRefused) {
  PrepareParams p;
  p.max_faces = 100;
  try {
    prepare_vessel(capped_tube(), p);
    FAIL() << "the face limit was ignored";
  } catch (const PrepareError& e) {
    EXPECT_EQ(e.kind(), PrepareError::Kind::TooLarge) << e.what();
  }
}

}  // namespace
}  // namespace sutura::engine
