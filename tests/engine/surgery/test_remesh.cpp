// Constrained local remeshing (remesh.hpp) and the transfer of state and rest shape across it.
#include "sutura/engine/surgery/remesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "surgery_fixture.hpp"
#include "sutura/engine/compute_threads.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/sim/selection.hpp"
#include "sutura/engine/sim/static_solver.hpp"

namespace sutura::engine {
namespace {

using testing::Body;

double distance_to_polyline(const Vec3& p, const std::vector<Vec3>& c) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    const Vec3 d = c[i + 1] - c[i];
    const double t = std::clamp((p - c[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (c[i] + t * d)).norm());
  }
  return best;
}

TEST(Remesh, ARegionOfAStripGetsTheTargetLengthAndKeepsTheRest) {
  const SurfaceMesh m = make_strip({40.0, 10.0, 40, 10});
  RemeshParams p;
  p.target_edge_length = 0.5;
  p.region = faces_near_polyline(m, {Vec3(15, 0, 0), Vec3(25, 0, 0)}, 2.5);
  const RemeshResult r = remesh(m, p);
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  EXPECT_GT(r.mesh.num_faces(), m.num_faces());
  const double mean = mean_edge_length(r.mesh, r.region);
  EXPECT_GT(mean, 0.4);
  EXPECT_LT(mean, 0.65);
  EXPECT_GT(r.after.min_angle_deg, 25.0);
  // The surface stays the plane z = 0, the outline is unchanged.
  for (const Vec3& x : r.mesh.positions()) EXPECT_EQ(x.z(), 0.0);
  EXPECT_DOUBLE_EQ(r.mesh.boundary_loops().size(), 1.0);
  // Faces far from the region are the old ones, bit for bit, with identity maps.
  std::size_t kept = 0;
  for (std::size_t f = 0; f < r.mesh.num_faces(); ++f) {
    const FaceOrigin& o = r.maps.faces[f];
    if (o.kind == FaceOriginKind::Subface) {
      ++kept;
      EXPECT_EQ(o.bary, Eigen::Matrix3d::Identity());
      const auto nv = r.mesh.face_vertices(FaceId(f));
      const auto ov = m.face_vertices(o.parent);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(r.mesh.position(nv[k]), m.position(ov[k]));
    }
  }
  EXPECT_GT(kept, m.num_faces() - p.region->size() - 80);  // all but a rim of split neighbours
}

TEST(Remesh, ConstrainedVerticesAndPolylinesAreKept) {
  const SurfaceMesh m = make_strip({20.0, 10.0, 20, 10});
  // A zig-zag polyline of mesh edges across the middle, and two fixed vertices beside it.
  std::vector<VertexId> chain;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3& x = m.position(VertexId(v));
    if (std::abs(x.x() - 10.0) < 1e-9 && std::abs(x.y()) < 4.5) chain.emplace_back(v);
  }
  std::sort(chain.begin(), chain.end(), [&](VertexId a, VertexId b) {
    return m.position(a).y() < m.position(b).y();
  });
  ASSERT_GE(chain.size(), 9u);
  RemeshParams p;
  p.target_edge_length = 0.4;
  p.region = faces_near_polyline(m, {Vec3(10, -5, 0), Vec3(10, 5, 0)}, 3.0);
  std::vector<Vec3> line;
  for (std::size_t i = 0; i + 1 < chain.size(); ++i)
    p.constrained_edges.emplace_back(chain[i], chain[i + 1]);
  for (const VertexId v : chain) line.push_back(m.position(v));
  p.constrained_vertices.assign(m.num_vertices(), false);
  std::vector<VertexId> fixed;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3& x = m.position(VertexId(v));
    if (std::abs(x.x() - 8.0) < 1e-9 && std::abs(x.y()) < 1.5) {
      p.constrained_vertices[v] = true;
      fixed.emplace_back(v);
    }
  }
  ASSERT_FALSE(fixed.empty());
  const RemeshResult r = remesh(m, p);
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  // Fixed vertices are copies at their old place.
  for (const VertexId v : fixed) {
    bool found = false;
    for (std::size_t w = 0; w < r.mesh.num_vertices(); ++w) {
      const VertexOrigin& o = r.maps.vertices[w];
      if (o.kind == VertexOriginKind::Copy && o.parents[0] == v) {
        found = true;
        EXPECT_EQ(r.mesh.position(VertexId(w)), m.position(v));
      }
    }
    EXPECT_TRUE(found) << "fixed vertex " << v.value << " was removed";
  }
  // The constrained edges were refined along the line and never left it; their ends stay.
  ASSERT_GT(r.constrained_edges.size(), chain.size() - 1);
  double length = 0.0;
  for (const auto& [a, b] : r.constrained_edges) {
    EXPECT_LT(distance_to_polyline(r.mesh.position(a), line), 1e-9);
    EXPECT_LT(distance_to_polyline(r.mesh.position(b), line), 1e-9);
    length += (r.mesh.position(a) - r.mesh.position(b)).norm();
  }
  EXPECT_NEAR(length, (line.back() - line.front()).norm(), 1e-9);
}

// Two fixed vertices a third of the target apart force thin faces on the short edge between
// them: raising the corners of thin faces lifts the region's smallest angle and moves no
// fixed vertex.
// RemeshParams::rim_faces_in_region: the faces outside the region that a remesh at half the
// spacing splits at the region's rim are reported as remeshed; with it, every face outside
// the reported region is an old face, bit for bit.
TEST(Remesh, FacesChangedAtTheRegionsRimCountAsRemeshed) {
  const SurfaceMesh m = make_strip({40.0, 10.0, 40, 10});
  RemeshParams p;
  p.target_edge_length = 0.5;
  p.region = faces_near_polyline(m, {Vec3(15, 0, 0), Vec3(25, 0, 0)}, 2.5);
  std::size_t changed_outside[2];
  for (const bool rim : {false, true}) {
    p.passes.rim_faces_in_region = rim;
    const RemeshResult r = remesh(m, p);
    ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
    std::vector<bool> in(r.mesh.num_faces(), false);
    for (const FaceId f : r.region) in[f.index()] = true;
    changed_outside[rim] = 0;
    for (std::size_t f = 0; f < r.mesh.num_faces(); ++f)
      if (!in[f] && r.maps.faces[f].kind != FaceOriginKind::Subface) ++changed_outside[rim];
    EXPECT_EQ(r.after.faces, r.region.size());
  }
  EXPECT_GT(changed_outside[0], 0u);  // what the test is about: the rim was split
  EXPECT_EQ(changed_outside[1], 0u);
}

TEST(Remesh, CornersOfThinFacesMoveAndTheSmallestAngleNeverFalls) {
  const SurfaceMesh grid = make_strip({20.0, 10.0, 20, 10});
  std::vector<Vec3> x = grid.positions();
  VertexId a, b;
  for (std::size_t v = 0; v < x.size(); ++v) {
    if ((x[v] - Vec3(10, 0, 0)).norm() < 1e-9) a = VertexId(v);
    if ((x[v] - Vec3(11, 0, 0)).norm() < 1e-9) b = VertexId(v);
  }
  ASSERT_TRUE(a.valid() && b.valid());
  x[b.index()] = Vec3(10.3, 0.05, 0.0);
  const SurfaceMesh m(x, grid.faces());
  RemeshParams p;
  p.target_edge_length = 1.0;
  p.region = faces_near_polyline(m, {Vec3(10, 0, 0)}, 4.0);
  p.constrained_vertices.assign(m.num_vertices(), false);
  p.constrained_vertices[a.index()] = p.constrained_vertices[b.index()] = true;
  double smallest[2];
  for (const double raise : {0.0, 25.0}) {
    p.passes.raise_angles_below_deg = raise;
    const RemeshResult r = remesh(m, p);
    ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
    smallest[raise > 0.0] = r.after.min_angle_deg;
    int kept = 0;
    for (std::size_t w = 0; w < r.mesh.num_vertices(); ++w) {
      const VertexOrigin& o = r.maps.vertices[w];
      if (o.kind == VertexOriginKind::Copy && (o.parents[0] == a || o.parents[0] == b)) {
        EXPECT_EQ(r.mesh.position(VertexId(w)), m.position(o.parents[0]));
        ++kept;
      }
    }
    EXPECT_EQ(kept, 2);
  }
  std::printf("smallest angle: %.2f deg without raising, %.2f deg with\n", smallest[0], smallest[1]);
  EXPECT_LT(smallest[0], 25.0);
  EXPECT_GT(smallest[1], smallest[0] + 1.0);
}

// The region around small angles: the faces touching a corner of a face below the limit
// (radius 0), more within a radius along the edges, none on another sheet close by in space.
TEST(Remesh, TheRegionAroundSmallAnglesFollowsTheEdges) {
  const SurfaceMesh grid = make_strip({20.0, 10.0, 20, 10});  // right triangles: 45 degrees
  std::vector<Vec3> x = grid.positions();
  VertexId b;
  for (std::size_t v = 0; v < x.size(); ++v)
    if ((x[v] - Vec3(11, 0, 0)).norm() < 1e-9) b = VertexId(v);
  ASSERT_TRUE(b.valid());
  x[b.index()] = Vec3(10.3, 0.05, 0.0);
  // A second, undistorted sheet 0.1 mm above the first: near in space, far along the edges.
  std::vector<Vec3> positions = x;
  std::vector<FaceIndices> faces = grid.faces();
  for (const Vec3& p : grid.positions()) positions.push_back(p + Vec3(0, 0, 0.1));
  const int n = int(grid.num_vertices());
  for (const FaceIndices& f : grid.faces()) faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  const SurfaceMesh m(positions, faces);

  EXPECT_TRUE(faces_near_small_angles(grid, 20.0, 5.0).empty());  // 45 degrees everywhere
  std::vector<bool> small_corner(m.num_vertices(), false);
  std::size_t small = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const auto v = m.face_vertices(FaceId(f));
    if (smallest_angle_deg(m.position(v[0]), m.position(v[1]), m.position(v[2])) >= 20.0) continue;
    ++small;
    for (const VertexId w : v) small_corner[w.index()] = true;
  }
  ASSERT_GT(small, 0u);
  const std::vector<FaceId> touching = faces_near_small_angles(m, 20.0, 0.0);
  std::size_t expected = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const auto v = m.face_vertices(FaceId(f));
    expected += small_corner[v[0].index()] || small_corner[v[1].index()] || small_corner[v[2].index()];
  }
  EXPECT_EQ(touching.size(), expected);
  const std::vector<FaceId> wider = faces_near_small_angles(m, 20.0, 1.5);
  EXPECT_GT(wider.size(), touching.size());
  EXPECT_TRUE(std::includes(wider.begin(), wider.end(), touching.begin(), touching.end()));
  for (const FaceId f : wider) {
    EXPECT_LT(f.index(), grid.num_faces()) << "a face of the other sheet";
    for (const VertexId v : m.face_vertices(f))  // within 1.5 mm along edges: 2.5 in space
      if (v.index() < grid.num_vertices()) {
        EXPECT_LT((m.position(v) - Vec3(10.3, 0.0, 0.0)).norm(), 4.0);
      }
  }
  for (const double bad : {0.0, -5.0, 61.0, std::nan("")})
    EXPECT_THROW(faces_near_small_angles(m, bad, 1.0), InvalidArgument) << bad;
  for (const double bad : {-1.0, std::nan(""), HUGE_VAL})
    EXPECT_THROW(faces_near_small_angles(m, 20.0, bad), InvalidArgument) << bad;
}

TEST(Remesh, GradedSizingIsFinestAtTheCurveAndGrowsToTheHost) {
  const SurfaceMesh m = make_strip({40.0, 20.0, 40, 20});  // host spacing 1 mm
  RemeshParams p;
  p.target_edge_length = 0.25;
  p.grading = 1.6;
  p.grading_curve = {Vec3(12, 0, 0), Vec3(28, 0, 0)};
  p.region = faces_near_polyline(m, p.grading_curve, 7.0);
  const RemeshResult r = remesh(m, p);
  ASSERT_TRUE(r.mesh.validate().ok()) << r.mesh.validate().summary();
  std::vector<FaceId> near, far;
  for (const FaceId f : r.region) {
    const auto v = r.mesh.face_vertices(f);
    const Vec3 c = (r.mesh.position(v[0]) + r.mesh.position(v[1]) + r.mesh.position(v[2])) / 3.0;
    const double d = distance_to_polyline(c, p.grading_curve);
    if (d < 0.4) near.push_back(f);
    if (d > 4.0) far.push_back(f);
  }
  ASSERT_FALSE(near.empty());
  ASSERT_FALSE(far.empty());
  EXPECT_LT(mean_edge_length(r.mesh, near), 0.35);
  EXPECT_GT(mean_edge_length(r.mesh, far), 0.7);
  EXPECT_GT(r.after.min_angle_deg, 20.0);
}

TEST(Remesh, IsDeterministicOnAnyThreadCount) {
  const SurfaceMesh m = make_tube({3.0, 20.0, 24, 20});
  RemeshParams p;
  p.target_edge_length = 0.35;
  p.grading = 1.5;
  p.grading_curve = {Vec3(3, 0, 8), Vec3(0, 3, 12)};
  p.region = faces_near_polyline(m, p.grading_curve, 3.0);
  set_compute_threads(1);
  const RemeshResult a = remesh(m, p);
  set_compute_threads(2);
  const RemeshResult b = remesh(m, p);
  ASSERT_EQ(a.mesh.faces(), b.mesh.faces());
  ASSERT_EQ(a.mesh.positions(), b.mesh.positions());
  ASSERT_EQ(a.maps.faces.size(), b.maps.faces.size());
  for (std::size_t f = 0; f < a.maps.faces.size(); ++f) EXPECT_EQ(a.maps.faces[f].bary, b.maps.faces[f].bary);
}

// An unstressed curved body stays unstressed: energy and forces zero to round-off, with both
// shell models, although the new faces cut across old faces at an angle.
TEST(Remesh, AnUnstressedTubeStaysUnstressed) {
  for (const bool discrete : {false, true}) {
    Body body(make_tube({3.0, 20.0, 24, 20}));
    RemeshParams p;
    p.target_edge_length = 0.3;
    p.grading = 1.5;
    p.grading_curve = {Vec3(3, 0, 8), Vec3(0, 3, 12)};
    p.region = faces_near_polyline(body.mesh, p.grading_curve, 3.0);
    const RemeshResult r = remesh(body.mesh, p);
    std::size_t resampled = 0;
    for (const auto& o : r.maps.faces) resampled += o.kind == FaceOriginKind::Resampled;
    ASSERT_GT(resampled, 100u);
    body.apply(r.mesh, r.maps);
    const auto model = discrete ? make_discrete_shell() : make_corotational_shell();
    const auto [energy, force] = testing::energy_and_force(*model, body);
    EXPECT_LT(std::abs(energy), 1e-20) << model->name();
    EXPECT_LT(force, 1e-10) << model->name();
  }
}

// A pressurised tube held at both ends, remeshed at its equilibrium in the middle of a run:
// the equilibrium found again on the new mesh moves the probed radius by under 1 %.
TEST(Remesh, AStressedTubeKeepsItsEquilibriumAcrossARemesh) {
  Body body(make_tube({4.0, 20.0, 24, 24}));
  ShellMaterial mat;
  mat.youngs_modulus = 1.0;
  mat.poisson_ratio = 0.45;
  mat.thickness = 0.3;
  const auto model = make_corotational_shell();
  const std::vector<ShellMaterial> mats{mat};
  auto solve = [&](Body& b) {
    ShellSystem sys;
    sys.model = model.get();
    sys.problem = ShellProblem{&b.mesh.faces(), &b.rest, &mats, &b.face_material, b.mesh.num_vertices()};
    for (double z : {0.0, 20.0})
      sys.constraints.fix(select_vertices(b.reference, SelectPlaneBand{Vec3(0, 0, z), Vec3(0, 0, 1), 1e-9}),
                          kAllDofs, b.mesh.num_vertices());
    sys.fixed_loads.pressures.push_back({{}, 0.0107});
    const StaticResult res = solve_static(sys, b.state, StaticSolverParams{});
    EXPECT_TRUE(res.converged) << res.message;
    b.mesh.set_positions(b.state.x);
  };
  // Mean radial displacement of the material points near the middle ring.
  auto probe = [](const Body& b) {
    double sum = 0.0;
    int n = 0;
    for (std::size_t v = 0; v < b.state.x.size(); ++v)
      if (std::abs(b.reference[v].z() - 10.0) < 1.5) {
        sum += b.state.x[v].head<2>().norm() - b.reference[v].head<2>().norm();
        ++n;
      }
    return sum / n;
  };
  solve(body);
  const double before = probe(body);
  ASSERT_GT(before, 0.1);
  RemeshParams p;
  p.target_edge_length = 0.5;  // half the host's spacing: every face of the band is new
  // A band across the middle of the tube, all the way round.
  p.region.emplace();
  for (std::size_t f = 0; f < body.mesh.num_faces(); ++f) {
    const auto v = body.mesh.face_vertices(FaceId(f));
    if (std::abs(body.reference[v[0].index()].z() - 10.0) < 3.0) p.region->emplace_back(f);
  }
  const RemeshResult r = remesh(body.mesh, p);
  body.apply(r.mesh, r.maps);
  check_attributes(body.mesh, body);
  const double carried = probe(body);
  solve(body);
  const double after = probe(body);
  EXPECT_LT(std::abs(after - before), 0.01 * before) << before << " -> " << after;
  EXPECT_LT(std::abs(after - carried), 0.01 * before);
}

TEST(Remesh, BadInputIsRefusedNamingTheField) {
  const SurfaceMesh m = make_strip({10.0, 4.0, 10, 4});
  auto message = [&](const RemeshParams& p) {
    try {
      (void)remesh(m, p);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  RemeshParams p;
  p.target_edge_length = 0.0;
  EXPECT_NE(message(p).find("target_edge_length"), std::string::npos);
  p.target_edge_length = 50.0;
  EXPECT_NE(message(p).find("target_edge_length"), std::string::npos) << message(p);
  p.target_edge_length = 1e-5;
  EXPECT_NE(message(p).find("target_edge_length"), std::string::npos) << message(p);
  p.target_edge_length = 0.5;
  p.region = std::vector<FaceId>{FaceId(100000)};
  EXPECT_NE(message(p).find("region"), std::string::npos);
  p.region = faces_near_polyline(m, {Vec3(100, 100, 0)}, 1.0);
  EXPECT_NE(message(p).find("region"), std::string::npos);
  p.region.reset();
  p.grading = 0.5;
  EXPECT_NE(message(p).find("grading"), std::string::npos);
  p.grading = 1.0;
  p.passes.iterations = 0;
  EXPECT_NE(message(p).find("iterations"), std::string::npos);
  p.passes.iterations = 3;
  p.passes.raise_angles_below_deg = -1.0;
  EXPECT_NE(message(p).find("raise_angles_below_deg"), std::string::npos);
  p.passes.raise_angles_below_deg = std::nan("");
  EXPECT_NE(message(p).find("raise_angles_below_deg"), std::string::npos);
  p.passes.raise_angles_below_deg = 25.0;
  p.constrained_edges = {{VertexId(0), VertexId(30)}};
  EXPECT_NE(message(p).find("constrained_edges"), std::string::npos);
  p.constrained_edges.clear();
  p.constrained_vertices.assign(3, true);
  EXPECT_NE(message(p).find("constrained_vertices"), std::string::npos);
}

}  // namespace
}  // namespace sutura::engine
