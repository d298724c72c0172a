// Synthetic aortic arch: topology, open ends, cross-sections at the coarctation, element
// quality, clearance between the vessels, determinism, parameter errors, and that the shipped
// assets (assets/anatomy/) are exactly what the generator produces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/mesh_io.hpp"
#include "temp_dir.hpp"

namespace sutura::engine {
namespace {

const std::filesystem::path kAssets = std::filesystem::path(SUTURA_ASSETS_DIR) / "anatomy";

// Generation takes seconds: each configuration is generated once per test run.
const ArchAnatomy& coarse() {
  static const ArchAnatomy a = generate_arch(ArchParams{});
  return a;
}

ArchParams fine_params() {
  ArchParams p;
  p.target_edge_length = kArchFineEdgeLength;
  return p;
}

const ArchAnatomy& fine() {
  static const ArchAnatomy a = generate_arch(fine_params());
  return a;
}

double min_angle_deg(const SurfaceMesh& mesh) {
  double lo = 180.0;
  for (const auto& f : mesh.faces())
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.positions()[f[k]];
      const Vec3 a = mesh.positions()[f[(k + 1) % 3]] - p;
      const Vec3 b = mesh.positions()[f[(k + 2) % 3]] - p;
      lo = std::min(lo, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi);
    }
  return lo;
}

std::size_t connected_components(const SurfaceMesh& mesh) {
  std::vector<int> seen(mesh.num_faces(), 0);
  std::size_t count = 0;
  for (std::size_t start = 0; start < mesh.num_faces(); ++start) {
    if (seen[start]) continue;
    ++count;
    std::vector<std::size_t> stack{start};
    seen[start] = 1;
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const HalfedgeId t = mesh.twin(SurfaceMesh::halfedge(FaceId(f), k));
        if (!t.valid()) continue;
        const std::size_t g = SurfaceMesh::face(t).index();
        if (!seen[g]) seen[g] = 1, stack.push_back(g);
      }
    }
  }
  return count;
}

// Volume enclosed by the surface with each boundary loop capped by a fan to its centroid.
// Positive exactly when the normals point outwards.
double capped_volume(const SurfaceMesh& mesh) {
  double six_v = 0.0;
  for (const auto& f : mesh.faces())
    six_v += mesh.positions()[f[0]].dot(mesh.positions()[f[1]].cross(mesh.positions()[f[2]]));
  for (const auto& loop : mesh.boundary_loops()) {
    Vec3 c = Vec3::Zero();
    for (VertexId v : loop) c += mesh.position(v);
    c /= static_cast<double>(loop.size());
    for (std::size_t i = 0; i < loop.size(); ++i) {  // cap faces run against the boundary
      const Vec3& a = mesh.position(loop[i]);
      const Vec3& b = mesh.position(loop[(i + 1) % loop.size()]);
      six_v += c.dot(b.cross(a));
    }
  }
  return six_v / 6.0;
}

// Points where mesh edges cross the plane (centre, unit normal), within `reach` of centre.
std::vector<Vec3> section(const SurfaceMesh& mesh, const Vec3& centre, const Vec3& normal,
                          double reach) {
  std::vector<Vec3> out;
  for (HalfedgeId h : mesh.edges()) {
    const Vec3& a = mesh.position(mesh.from_vertex(h));
    const Vec3& b = mesh.position(mesh.to_vertex(h));
    const double sa = (a - centre).dot(normal), sb = (b - centre).dot(normal);
    if ((sa < 0.0) == (sb < 0.0)) continue;
    const Vec3 p = a + sa / (sa - sb) * (b - a);
    if ((p - centre).norm() < reach) out.push_back(p);
  }
  return out;
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Closest point on a triangle (Ericson, Real-Time Collision Detection, 5.1.5).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * vb * denom + ac * vc * denom)).norm();
}

// Smallest distance from the vertices of `a` to the triangles of `b`.
double vertex_to_surface_distance(const SurfaceMesh& a, const SurfaceMesh& b) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& p : a.positions())
    for (const auto& f : b.faces())
      best = std::min(best, point_triangle_distance(p, b.positions()[f[0]], b.positions()[f[1]],
                                                    b.positions()[f[2]]));
  return best;
}

void expect_clean_vessel(const SurfaceMesh& mesh, const std::vector<VesselEnd>& ends) {
  const auto report = mesh.validate();
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_EQ(connected_components(mesh), 1u);
  EXPECT_GT(capped_volume(mesh), 0.0) << "normals must point outwards";
  const auto loops = mesh.boundary_loops();
  ASSERT_EQ(loops.size(), ends.size());
  // Every end has exactly one loop, and every loop vertex lies in the end plane on the circle
  // of the end radius (border vertices are projected onto plane ∩ implicit surface).
  for (const VesselEnd& e : ends) {
    int matching = 0;
    for (const auto& loop : loops) {
      if ((mesh.position(loop.front()) - e.centre).norm() > 1.5 * e.radius) continue;
      ++matching;
      EXPECT_GE(loop.size(), 6u) << e.name;
      for (VertexId v : loop) {
        const Vec3 d = mesh.position(v) - e.centre;
        EXPECT_NEAR(d.dot(e.normal), 0.0, 1e-9) << e.name;
        EXPECT_NEAR(d.norm(), e.radius, 1e-6) << e.name;
      }
    }
    EXPECT_EQ(matching, 1) << e.name;
  }
}

TEST(AorticArch, AortaIsOneCleanManifoldWithFiveOpenEnds) {
  const ArchAnatomy& a = coarse();
  EXPECT_EQ(a.landmarks.aorta_ends.size(), 5u);
  expect_clean_vessel(a.aorta, a.landmarks.aorta_ends);
}

TEST(AorticArch, PulmonaryArteryIsOneCleanManifoldWithThreeOpenEnds) {
  const ArchAnatomy& a = coarse();
  EXPECT_EQ(a.landmarks.pulmonary_ends.size(), 3u);
  expect_clean_vessel(a.pulmonary, a.landmarks.pulmonary_ends);
}

TEST(AorticArch, LsaOnlyVariantHasThreeAorticEnds) {
  ArchParams p;
  p.head_neck_branches = false;
  const ArchAnatomy a = generate_arch(p);
  ASSERT_EQ(a.landmarks.aorta_ends.size(), 3u);
  expect_clean_vessel(a.aorta, a.landmarks.aorta_ends);
}

TEST(AorticArch, FaceCountsAndMinimumAngles) {
  // Isotropic remeshing aims at equilateral triangles; 15 degrees is the usual bound below
  // which shell elements (DKT, ANDES) lose accuracy, and a repaired mesh keeps 20 (issue 22):
  // the generator's closing repair smooths every face below 22 (measured: 29.8, 26.2, 22.8,
  // 24.4; the fine aorta had 18.8 before it).
  EXPECT_GT(coarse().aorta.num_faces(), 3000u);
  EXPECT_LT(coarse().aorta.num_faces(), 5000u);
  EXPECT_GT(fine().aorta.num_faces(), 18000u);
  EXPECT_LT(fine().aorta.num_faces(), 22000u);
  EXPECT_GT(min_angle_deg(coarse().aorta), 22.0);
  EXPECT_GT(min_angle_deg(coarse().pulmonary), 22.0);
  EXPECT_GT(min_angle_deg(fine().aorta), 22.0);
  EXPECT_GT(min_angle_deg(fine().pulmonary), 22.0);
  EXPECT_NEAR(coarse().aorta.mean_edge_length(), kArchCoarseEdgeLength, 0.15 * kArchCoarseEdgeLength);
  EXPECT_NEAR(fine().aorta.mean_edge_length(), kArchFineEdgeLength, 0.15 * kArchFineEdgeLength);
}

TEST(AorticArch, CoarctationLandmarksFollowTheParameters) {
  const ArchParams p;
  const ArchLandmarks& l = coarse().landmarks;
  EXPECT_DOUBLE_EQ(l.coarctation_min_radius, p.coarctation_fraction * p.descending_diameter / 2);
  EXPECT_DOUBLE_EQ(l.coarctation_length, p.coarctation_length);
  EXPECT_NEAR(l.coarctation_axis.norm(), 1.0, 1e-12);
  EXPECT_NEAR(l.lsa_axis.norm(), 1.0, 1e-12);
  // The coarctation lies coarctation_offset along the centreline distal to the LSA origin:
  // the straight distance is a little shorter on the curved arch.
  const double to_coarctation = (l.coarctation_centre - l.lsa_origin).norm();
  EXPECT_GT(to_coarctation, 0.5 * p.coarctation_offset);
  EXPECT_LT(to_coarctation, p.coarctation_offset + p.distal_arch_diameter);
  EXPECT_NEAR((l.lsa_tip - l.lsa_origin).dot(l.lsa_axis), (l.lsa_tip - l.lsa_origin).norm(), 1e-9);
  EXPECT_LT((l.lsa_tip - l.lsa_origin).norm(), p.lsa_length);
  // The ostium lies on the aortic wall: the aortic centreline is about one radius away.
  const Centreline& aorta = l.centrelines.front();
  ASSERT_EQ(aorta.name, "aorta");
  double wall = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < aorta.points.size(); ++i)
    wall = std::min(wall, (aorta.points[i] - l.lsa_origin).norm() - aorta.radii[i]);
  EXPECT_NEAR(wall, 0.0, 0.05);
}

// Cross-sections normal to the centreline around the coarctation have the radius of the
// profile. The mesh is piecewise linear with vertices on the exact surface, so it deviates
// from it by at most l^2 / 8 times the largest principal curvature (l: longest edge, up to
// 4/3 of the target after isotropic remeshing): 1 / r around, and r'' along the throat,
// where the raised-cosine narrowing gives r'' = pi^2 (r_base - r_min) / (2 (length / 2)^2)
// ~ 1.8 / mm for the defaults. Fine mesh: about 0.1 mm.
TEST(AorticArch, CrossSectionsThroughTheCoarctationMatchTheProfile) {
  const ArchParams p = fine_params();
  const ArchAnatomy& a = fine();
  const Centreline& aorta = a.landmarks.centrelines.front();
  std::size_t c = 0;
  for (std::size_t i = 0; i < aorta.points.size(); ++i)
    if ((aorta.points[i] - a.landmarks.coarctation_centre).norm() <
        (aorta.points[c] - a.landmarks.coarctation_centre).norm())
      c = i;
  const double r_min = a.landmarks.coarctation_min_radius;
  const double curvature = std::max(1.0 / r_min, std::numbers::pi * std::numbers::pi *
                                                     (p.isthmus_diameter / 2 - r_min) /
                                                     (2.0 * std::pow(p.coarctation_length / 2, 2)));
  double longest = 0.0;
  for (HalfedgeId h : a.aorta.edges())
    longest = std::max(longest, (a.aorta.position(a.aorta.to_vertex(h)) -
                                 a.aorta.position(a.aorta.from_vertex(h))).norm());
  EXPECT_LT(longest, 1.5 * p.target_edge_length);
  const double tol = longest * longest / 8.0 * curvature + 0.01;
  for (std::size_t i = c - 10; i <= c + 10; ++i) {
    const Vec3 normal = (aorta.points[i + 1] - aorta.points[i - 1]).normalized();
    const auto pts = section(a.aorta, aorta.points[i], normal, 1.5 * aorta.radii[i]);
    ASSERT_GE(pts.size(), 6u) << "section " << i;
    double mean = 0.0;
    for (const Vec3& q : pts) {
      EXPECT_NEAR((q - aorta.points[i]).norm(), aorta.radii[i], tol) << "section " << i;
      mean += (q - aorta.points[i]).norm() / static_cast<double>(pts.size());
    }
    EXPECT_NEAR(mean, aorta.radii[i], tol) << "section " << i;
  }
  // The coarctation is the narrowest section of the aorta (centreline samples are <= 0.5 mm
  // apart, so the nearest one is within 1e-3 mm of the minimum radius).
  EXPECT_NEAR(aorta.radii[c], r_min, 1e-3);
  EXPECT_GE(*std::min_element(aorta.radii.begin(), aorta.radii.end()), r_min);
}

TEST(AorticArch, PulmonaryArteryKeepsClearOfTheAorta) {
  const ArchParams p;
  const ArchAnatomy& a = coarse();
  const double d = std::min(vertex_to_surface_distance(a.pulmonary, a.aorta),
                            vertex_to_surface_distance(a.aorta, a.pulmonary));
  // The centreline layout guarantees pulmonary_gap between the ideal walls; the smooth union
  // may bulge junctions by up to blend / 4.
  EXPECT_GT(d, p.pulmonary_gap - p.junction_blend / 4);
}

TEST(AorticArch, GenerationIsDeterministic) {
  const ArchAnatomy again = generate_arch(ArchParams{});
  EXPECT_EQ(again.aorta.faces(), coarse().aorta.faces());
  EXPECT_EQ(again.pulmonary.faces(), coarse().pulmonary.faces());
  ASSERT_EQ(again.aorta.positions().size(), coarse().aorta.positions().size());
  for (std::size_t i = 0; i < again.aorta.positions().size(); ++i)
    ASSERT_EQ(again.aorta.positions()[i], coarse().aorta.positions()[i]) << "vertex " << i;
  for (std::size_t i = 0; i < again.pulmonary.positions().size(); ++i)
    ASSERT_EQ(again.pulmonary.positions()[i], coarse().pulmonary.positions()[i]) << "vertex " << i;
}

void expect_rejected(const std::function<void(ArchParams&)>& edit, const std::string& field) {
  ArchParams p;
  edit(p);
  try {
    (void)generate_arch(p);
    ADD_FAILURE() << "accepted bad " << field;
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(AorticArch, BadParametersAreRejectedNamingTheField) {
  expect_rejected([](ArchParams& p) { p.ascending_diameter = -8.0; }, "ascending_diameter");
  expect_rejected([](ArchParams& p) { p.descending_diameter = std::nan(""); }, "descending_diameter");
  expect_rejected([](ArchParams& p) { p.coarctation_fraction = 0.1; }, "coarctation_fraction");
  expect_rejected([](ArchParams& p) { p.coarctation_fraction = 0.95; }, "coarctation_fraction");
  expect_rejected([](ArchParams& p) { p.coarctation_offset = 0.5; }, "coarctation_offset");
  expect_rejected([](ArchParams& p) { p.coarctation_offset = 60.0; }, "coarctation_offset");
  expect_rejected([](ArchParams& p) { p.carotid_angle_deg = 30.0; }, "carotid_angle_deg");
  expect_rejected([](ArchParams& p) { p.subclavian_angle_deg = 185.0; }, "subclavian_angle_deg");
  expect_rejected([](ArchParams& p) { p.arch_radius = 3.0; }, "arch_radius");
  expect_rejected([](ArchParams& p) { p.lsa_length = 3.0; }, "lsa_length");
  expect_rejected([](ArchParams& p) { p.target_edge_length = 0.0; }, "target_edge_length");
  expect_rejected([](ArchParams& p) { p.target_edge_length = 1.8; }, "target_edge_length");
  expect_rejected([](ArchParams& p) { p.pulmonary_branch_diameter = 7.0; }, "pulmonary_gap");
  expect_rejected([](ArchParams& p) { p.carotid_angle_deg = 45.0; }, "innominate");
}

std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void expect_vec(const nlohmann::json& j, const Vec3& v, const std::string& what) {
  ASSERT_EQ(j.size(), 3u) << what;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(j[k].get<double>(), v[k]) << what;
}

// The shipped meshes are byte-identical to a regeneration, and the shipped landmarks hold
// exactly the generated values, so the assets never drift from the code.
void expect_assets_match(const std::string& resolution, const ArchAnatomy& a) {
  const auto dir = kAssets / resolution;
  testing::TempDir tmp;
  save_mesh(a.aorta, tmp.path() / "aorta.ply");
  save_mesh(a.pulmonary, tmp.path() / "pulmonary.ply");
  EXPECT_TRUE(file_bytes(tmp.path() / "aorta.ply") == file_bytes(dir / "aorta.ply"))
      << resolution << "/aorta.ply differs from a regeneration; see assets/anatomy/README.md";
  EXPECT_TRUE(file_bytes(tmp.path() / "pulmonary.ply") == file_bytes(dir / "pulmonary.ply"))
      << resolution << "/pulmonary.ply differs from a regeneration; see assets/anatomy/README.md";

  std::ifstream in(dir / "landmarks.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const ArchLandmarks& l = a.landmarks;
  EXPECT_EQ(j["aorta"]["mesh"]["faces"].get<std::size_t>(), a.aorta.num_faces());
  EXPECT_EQ(j["pulmonary"]["mesh"]["faces"].get<std::size_t>(), a.pulmonary.num_faces());
  expect_vec(j["coarctation"]["centre"], l.coarctation_centre, "coarctation centre");
  expect_vec(j["coarctation"]["axis"], l.coarctation_axis, "coarctation axis");
  EXPECT_EQ(j["coarctation"]["min_radius"].get<double>(), l.coarctation_min_radius);
  expect_vec(j["left_subclavian"]["origin"], l.lsa_origin, "LSA origin");
  expect_vec(j["left_subclavian"]["tip"], l.lsa_tip, "LSA tip");
  ASSERT_EQ(j["aorta"]["ends"].size(), l.aorta_ends.size());
  for (std::size_t i = 0; i < l.aorta_ends.size(); ++i) {
    EXPECT_EQ(j["aorta"]["ends"][i]["name"].get<std::string>(), l.aorta_ends[i].name);
    expect_vec(j["aorta"]["ends"][i]["centre"], l.aorta_ends[i].centre, l.aorta_ends[i].name);
  }
  ASSERT_EQ(j["centrelines"].size(), l.centrelines.size());
  for (std::size_t i = 0; i < l.centrelines.size(); ++i)
    EXPECT_EQ(j["centrelines"][i]["radii"].get<std::vector<double>>(), l.centrelines[i].radii);
}

TEST(AorticArch, ShippedCoarseAssetsMatchARegeneration) { expect_assets_match("coarse", coarse()); }

TEST(AorticArch, ShippedFineAssetsMatchARegeneration) { expect_assets_match("fine", fine()); }

}  // namespace
}  // namespace sutura::engine
