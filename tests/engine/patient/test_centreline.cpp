// extract_centreline: the automatic centreline against the generated arch's analytic one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/measure/centreline.hpp"
#include "tree_distance.hpp"

namespace sutura::engine {
namespace {

TEST(Centreline, TubeAxis) {
  TubeParams p;
  p.radius = 3.0;
  p.length = 30.0;
  p.segments_around = 32;
  p.segments_along = 60;
  const SurfaceMesh tube = make_tube(p);
  const CentrelineTree t = extract_centreline(tube);
  ASSERT_EQ(t.end_nodes.size(), 2u);
  EXPECT_TRUE(t.branch_points.empty());
  double worst = 0.0;
  for (double z = 3.0; z <= 27.0; z += 0.5) worst = std::max(worst, distance_to_tree(t, Vec3(0, 0, z)));
  EXPECT_LT(worst, 0.01);
  // The radius: the distance to the 32-gon's faces, r cos(pi / 32), away from the ends.
  for (std::size_t v = 0; v < t.points.size(); ++v)
    if (t.points[v].z() > 3.0 && t.points[v].z() < 27.0) {
      EXPECT_NEAR(t.radii[v], 3.0 * std::cos(M_PI / 32), 0.01);
    }
  const auto path = centreline_path(t, Vec3(0, 0, -1), Vec3(0, 0, 31));
  EXPECT_NEAR((path.front() - Vec3(0, 0, 0)).norm(), 0.0, 0.1);
  EXPECT_NEAR((path.back() - Vec3(0, 0, 30)).norm(), 0.0, 0.1);
}

// The generated arch (fine, 19k faces): every analytic centreline point lies within a tenth of
// its lumen radius of the tree, except in the junctions, where the analytic centrelines meet
// at a point on the aortic axis but the lumen is the blend of two vessels. A junction is the
// ball around a branch's origin (its first centreline point, on the aortic axis) of radius the
// aortic plus the branch radius.
TEST(Centreline, ArchAgainstItsAnalyticCentrelines) {
  ArchParams p;
  p.target_edge_length = kArchFineEdgeLength;
  const ArchAnatomy arch = generate_arch(p);
  const CentrelineTree t = extract_centreline(arch.aorta, arch.landmarks.aorta_ends);
  ASSERT_EQ(t.end_nodes.size(), 5u);
  EXPECT_EQ(t.branch_points.size(), 3u);
  for (std::size_t e = 0; e < t.end_nodes.size(); ++e)
    EXPECT_LT((t.points[t.end_nodes[e]] - arch.landmarks.aorta_ends[e].centre).norm(), 1e-12);
  struct Junction {
    Vec3 centre;
    double radius;
  };
  std::vector<Junction> junctions;
  const Centreline* aorta = nullptr;
  for (const Centreline& c : arch.landmarks.centrelines)
    if (c.name == "aorta") aorta = &c;
  ASSERT_NE(aorta, nullptr);
  for (const Centreline& c : arch.landmarks.centrelines) {
    if (c.name == "aorta" || c.name.find("pulmonary") != std::string::npos) continue;
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < aorta->points.size(); ++i)
      if ((aorta->points[i] - c.points.front()).norm() < (aorta->points[nearest] - c.points.front()).norm()) nearest = i;
    junctions.push_back({c.points.front(), aorta->radii[nearest] + c.radii.front()});
  }
  ASSERT_EQ(junctions.size(), 3u);
  int checked = 0;
  for (const Centreline& c : arch.landmarks.centrelines) {
    if (c.name.find("pulmonary") != std::string::npos) continue;
    double worst = 0.0, worst_in_junction = 0.0;
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      bool in_junction = false;
      for (const Junction& j : junctions) in_junction |= (c.points[i] - j.centre).norm() < j.radius;
      const double d = distance_to_tree(t, c.points[i]);
      if (in_junction) {
        worst_in_junction = std::max(worst_in_junction, d);
        continue;
      }
      worst = std::max(worst, d / c.radii[i]);
      ++checked;
    }
    std::printf("%s: worst %.3f radii, in the junctions %.2f mm\n", c.name.c_str(), worst, worst_in_junction);
    EXPECT_LT(worst, 0.1) << c.name;
    // In a junction the tree still runs inside the lumen.
    EXPECT_LT(worst_in_junction, 1.0) << c.name;
  }
  EXPECT_GT(checked, 120);
  // The radius (distance to the wall) at the tree point nearest the coarctation's centre.
  std::size_t at_coarctation = 0;
  for (std::size_t v = 0; v < t.points.size(); ++v)
    if ((t.points[v] - arch.landmarks.coarctation_centre).norm() <
        (t.points[at_coarctation] - arch.landmarks.coarctation_centre).norm())
      at_coarctation = v;
  EXPECT_NEAR(t.radii[at_coarctation], arch.landmarks.coarctation_min_radius, 0.1 * arch.landmarks.coarctation_min_radius);
}

// Without named ends (what `measure` with "centreline": "auto" does), the widest loop is the
// root, and the path from the aortic root to the innominate's end stays in the aorta and the
// innominate: within their radius plus a millimetre of their analytic centrelines, never up
// the left common carotid (with the carotid as the root it did).
TEST(Centreline, WithoutNamedEndsTheWidestIsTheRoot) {
  const ArchAnatomy arch = generate_arch(ArchParams{});
  const CentrelineTree t = extract_centreline(arch.aorta);
  ASSERT_EQ(t.end_nodes.size(), 5u);
  EXPECT_EQ(t.branch_points.size(), 3u);
  EXPECT_LT((t.points[t.end_nodes[0]] - arch.landmarks.aorta_ends[0].centre).norm(), 0.1);
  const VesselEnd& innominate = arch.landmarks.aorta_ends[2];
  ASSERT_EQ(innominate.name, "innominate");
  const auto path = centreline_path(t, arch.landmarks.aorta_ends[0].centre, innominate.centre);
  for (const Vec3& p : path) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Centreline& c : arch.landmarks.centrelines)
      if (c.name == "aorta" || c.name == "innominate")
        for (std::size_t i = 0; i < c.points.size(); ++i)
          nearest = std::min(nearest, (p - c.points[i]).norm() - c.radii[i]);
    EXPECT_LT(nearest, 1.0) << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  }
}

TEST(Centreline, RefusesWhatItCannotFollow) {
  TubeParams p;
  const SurfaceMesh tube = make_tube(p);
  // An open end per given end, each matched to its own loop.
  const std::vector<VesselEnd> one{{"only", Vec3::Zero(), Vec3::UnitZ(), 1.0}};
  EXPECT_THROW(extract_centreline(tube, one), InvalidArgument);
  const std::vector<VesselEnd> same{{"a", Vec3::Zero(), -Vec3::UnitZ(), 1.0}, {"b", Vec3(0, 0, 1), -Vec3::UnitZ(), 1.0}};
  EXPECT_THROW(extract_centreline(tube, same), InvalidArgument);
  // A closed surface (its caps not opened) has no ends to run between.
  std::vector<FaceIndices> faces{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  const SurfaceMesh tetra({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, faces);
  EXPECT_THROW(extract_centreline(tetra), InvalidArgument);
  EXPECT_THROW(extract_centreline(SurfaceMesh{}), InvalidArgument);
}

TEST(Centreline, Deterministic) {
  const ArchAnatomy arch = generate_arch(ArchParams{});
  const CentrelineTree a = extract_centreline(arch.aorta, arch.landmarks.aorta_ends);
  const CentrelineTree b = extract_centreline(arch.aorta, arch.landmarks.aorta_ends);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.radii, b.radii);
  EXPECT_EQ(a.edges, b.edges);
}

}  // namespace
}  // namespace sutura::engine
