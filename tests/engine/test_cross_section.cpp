// Cross-sections, lumen profiles and per-vertex fields (sutura/engine/measure).
//
// Reference values. make_tube puts its vertices on rings z = j * dz at angles 2 pi i / n, and
// each quad between two rings is a planar vertical rectangle (its four corners project onto
// the chord between two neighbouring ring vertices). The tube is therefore exactly the prism
// over the inscribed regular n-gon, and any plane cutting all its side faces has a section
// whose projection along z is that n-gon (the crossing points on the diagonals lie on its
// chords). Hence, for a plane with unit normal m:
//   area      = A_n / |m_z|,   A_n = (n/2) R^2 sin(2 pi / n)
//   perimeter = sum over the n-gon's edges of the edge lifted into the plane
// exactly (up to round-off), whatever the plane's position and tilt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/measure/cross_section.hpp"
#include "sutura/engine/measure/lumen_profile.hpp"
#include "sutura/engine/measure/vertex_fields.hpp"

using namespace sutura::engine;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 5.0;
constexpr int kN = 32;

SurfaceMesh tube() { return make_tube({kR, 40.0, kN, 40}); }

double ngon_area(double r = kR, int n = kN) { return 0.5 * n * r * r * std::sin(2.0 * kPi / n); }

// Vertices of the inscribed n-gon scaled by (sx, sy): an ellipse-inscribed polygon.
std::vector<Eigen::Vector2d> polygon(double sx, double sy) {
  std::vector<Eigen::Vector2d> q;
  for (int i = 0; i < kN; ++i) {
    const double phi = 2.0 * kPi * i / kN;
    q.emplace_back(sx * kR * std::cos(phi), sy * kR * std::sin(phi));
  }
  return q;
}

// Minimum width of a centrally symmetric convex polygon: twice the smallest distance from the
// centre (origin) to an edge line.
double symmetric_min_width(const std::vector<Eigen::Vector2d>& q) {
  double best = HUGE_VAL;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Eigen::Vector2d a = q[i], e = q[(i + 1) % q.size()] - a;
    best = std::min(best, std::abs(a.x() * e.y() - a.y() * e.x()) / e.norm());
  }
  return 2.0 * best;
}

double perimeter(const std::vector<Eigen::Vector2d>& q) {
  double p = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) p += (q[(i + 1) % q.size()] - q[i]).norm();
  return p;
}

bool has_consecutive_duplicates(const CrossSection& cs) {
  for (std::size_t i = 0; i < cs.points.size(); ++i)
    if (cs.points[i] == cs.points[(i + 1) % cs.points.size()]) return true;
  return false;
}

SurfaceMesh scaled(const SurfaceMesh& m, const std::function<Vec3(const Vec3&)>& map) {
  std::vector<Vec3> p;
  for (const Vec3& x : m.positions()) p.push_back(map(x));
  return SurfaceMesh(std::move(p), m.faces());
}

}  // namespace

TEST(CrossSection, CircularTubeBetweenRingsIsTheInscribedPolygon) {
  const SurfaceMesh m = tube();
  const CrossSection cs = cross_section(m, {Vec3(0, 0, 10.3), Vec3(0, 0, 1)});
  EXPECT_TRUE(cs.closed);
  EXPECT_NEAR(cs.area, ngon_area(), 1e-12 * ngon_area());
  EXPECT_NEAR(cs.perimeter, 2.0 * kN * kR * std::sin(kPi / kN), 1e-12 * kR);
  EXPECT_NEAR(cs.equivalent_diameter, std::sqrt(4.0 * ngon_area() / kPi), 1e-12 * kR);
  EXPECT_NEAR(cs.max_diameter, 2.0 * kR, 1e-12 * kR);                        // opposite vertices
  EXPECT_NEAR(cs.min_diameter, 2.0 * kR * std::cos(kPi / kN), 1e-12 * kR);  // opposite edges
  EXPECT_LT((cs.centroid - Vec3(0, 0, 10.3)).norm(), 1e-12 * kR);
  EXPECT_EQ(cs.points.size(), 2u * kN);  // one crossing per vertical and per diagonal edge
  for (const Vec3& p : cs.points) EXPECT_NEAR(p.z(), 10.3, 1e-12);
}

TEST(CrossSection, PlaneThroughARingOfVerticesAndAlongItsEdges) {
  // Every ring vertex lies exactly on the plane and every ring edge in it: the outline must be
  // the ring itself, each vertex once.
  const SurfaceMesh m = tube();
  const CrossSection cs = cross_section(m, {Vec3(0, 0, 20.0), Vec3(0, 0, 1)});
  EXPECT_TRUE(cs.closed);
  ASSERT_EQ(cs.points.size(), static_cast<std::size_t>(kN));
  for (const Vec3& p : cs.points) EXPECT_EQ(p.z(), 20.0);
  EXPECT_NEAR(cs.area, ngon_area(), 1e-12 * ngon_area());
  EXPECT_NEAR(cs.perimeter, 2.0 * kN * kR * std::sin(kPi / kN), 1e-12 * kR);
  // The same ring seen with the normal reversed: counted on the other side, same outline.
  const CrossSection back = cross_section(m, {Vec3(0, 0, 20.0), Vec3(0, 0, -1)});
  EXPECT_TRUE(back.closed);
  EXPECT_NEAR(back.area, cs.area, 1e-12 * cs.area);
}

TEST(CrossSection, ObliquePlaneGivesTheEllipseWithinTheDiscretisationBound) {
  // The plane tilted by theta cuts the cylinder of radius R in an ellipse with semi-axes
  // a = R, b = R / cos(theta). The section is the affine image (y stretched by 1/cos theta) of
  // the inscribed n-gon, so area / (pi a b) = A_n / (pi R^2) = sin(x) / x with x = 2 pi / n,
  // and 1 - x^2/6 <= sin(x)/x <= 1: 0 <= pi a b - area <= pi a b (2 pi / n)^2 / 6.
  const double theta = 30.0 * kPi / 180.0;
  const SurfaceMesh m = tube();
  const CrossSection cs =
      cross_section(m, {Vec3(0, 0, 20.3), Vec3(0, std::sin(theta), std::cos(theta))});
  const double a = kR, b = kR / std::cos(theta);
  const double x = 2.0 * kPi / kN;
  EXPECT_TRUE(cs.closed);
  EXPECT_LE(cs.area, kPi * a * b);
  EXPECT_GE(cs.area, kPi * a * b * (1.0 - x * x / 6.0));
  EXPECT_NEAR(cs.area, ngon_area() / std::cos(theta), 1e-12 * cs.area);  // prism identity
  const auto q = polygon(1.0, 1.0 / std::cos(theta));                    // in-plane outline
  EXPECT_NEAR(cs.perimeter, perimeter(q), 1e-12 * kR);
  EXPECT_NEAR(cs.max_diameter, 2.0 * b, 1e-12 * kR);
  EXPECT_NEAR(cs.min_diameter, symmetric_min_width(q), 1e-12 * kR);
  EXPECT_LT((cs.centroid - Vec3(0, 0, 20.3)).norm(), 1e-12 * kR);
}

TEST(CrossSection, EllipticalTubeMinAndMaxDiameter) {
  const double a = 6.0, b = 3.0;
  const SurfaceMesh m = scaled(tube(), [&](const Vec3& p) {
    return Vec3(p.x() * a / kR, p.y() * b / kR, p.z());
  });
  const CrossSection cs = cross_section(m, {Vec3(0, 0, 10.5), Vec3(0, 0, 1)});
  const auto q = polygon(a / kR, b / kR);
  EXPECT_TRUE(cs.closed);
  EXPECT_NEAR(cs.max_diameter, 2.0 * a, 1e-12 * a);
  EXPECT_NEAR(cs.min_diameter, symmetric_min_width(q), 1e-12 * a);
  EXPECT_LT(cs.min_diameter, 2.0 * b);                     // an edge is nearer than the vertex
  EXPECT_GT(cs.min_diameter, 2.0 * b * std::cos(kPi / 8));  // ... but not much
  EXPECT_NEAR(cs.area, ngon_area() * a * b / (kR * kR), 1e-12 * a * b);
  EXPECT_NEAR(cs.perimeter, perimeter(q), 1e-12 * a);
}

TEST(CrossSection, TiltedPlaneThroughASingleVertex) {
  const SurfaceMesh m = tube();
  const Vec3 vertex = m.position(VertexId(20 * kN));  // ring 20, angle 0: (R, 0, 20)
  const double theta = 20.0 * kPi / 180.0;
  const CrossSection cs = cross_section(m, {vertex, Vec3(std::sin(theta), 0, std::cos(theta))});
  EXPECT_TRUE(cs.closed);
  EXPECT_FALSE(has_consecutive_duplicates(cs));
  EXPECT_EQ(std::count(cs.points.begin(), cs.points.end(), vertex), 1);
  EXPECT_NEAR(cs.area, ngon_area() / std::cos(theta), 1e-12 * cs.area);
}

TEST(CrossSection, TiltedPlaneAlongADiagonalEdge) {
  // Quad (i = 0, ring 20) is split along its diagonal from ring vertex 0 to ring-21 vertex 1.
  const SurfaceMesh m = tube();
  const Vec3 p0 = m.position(VertexId(20 * kN)), p1 = m.position(VertexId(21 * kN + 1));
  const Vec3 chord = Vec3(p1.x() - p0.x(), p1.y() - p0.y(), 0.0);
  Vec3 normal = (p1 - p0).cross(Vec3::UnitZ().cross(chord)).normalized();
  if (normal.z() < 0.0) normal = -normal;
  const CrossSection cs = cross_section(m, {p0, normal});
  EXPECT_TRUE(cs.closed);
  EXPECT_FALSE(has_consecutive_duplicates(cs));
  EXPECT_NEAR(cs.area, ngon_area() / normal.z(), 1e-12 * cs.area);
  // Both edge ends are on the outline (to round-off for the far end).
  double d0 = HUGE_VAL, d1 = HUGE_VAL;
  for (const Vec3& p : cs.points) d0 = std::min(d0, (p - p0).norm()), d1 = std::min(d1, (p - p1).norm());
  EXPECT_EQ(d0, 0.0);
  EXPECT_LT(d1, 1e-12 * kR);
}

TEST(CrossSection, TwoTubesTheLoopIsChosenByTheOrigin) {
  const SurfaceMesh a = tube();
  std::vector<Vec3> p = a.positions();
  std::vector<FaceIndices> f = a.faces();
  const auto offset = static_cast<std::int32_t>(p.size());
  for (const Vec3& x : a.positions()) p.push_back(x + Vec3(20, 0, 0));
  for (const FaceIndices& t : a.faces()) f.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const SurfaceMesh two(std::move(p), std::move(f));
  const Vec3 up(0, 0, 1);

  const CrossSection at_a = cross_section(two, {Vec3(0, 0, 10.5), up});
  EXPECT_TRUE(at_a.closed);
  EXPECT_NEAR(at_a.centroid.x(), 0.0, 1e-12);
  EXPECT_NEAR(at_a.area, ngon_area(), 1e-12 * ngon_area());
  const CrossSection at_b = cross_section(two, {Vec3(20, 0, 10.5), up});
  EXPECT_NEAR(at_b.centroid.x(), 20.0, 1e-12);
  // Inside neither: the nearest loop (B's wall is 2 mm away, A's 8 mm).
  EXPECT_NEAR(cross_section(two, {Vec3(13, 0, 10.5), up}).centroid.x(), 20.0, 1e-12);
  // A radius limit keeps B out entirely; around an empty region it finds nothing.
  CrossSectionParams near;
  near.max_radius = 6.0;
  const CrossSection limited = cross_section(two, {Vec3(0, 0, 10.5), up}, near);
  EXPECT_TRUE(limited.closed);
  EXPECT_NEAR(limited.centroid.x(), 0.0, 1e-12);
  EXPECT_THROW((void)cross_section(two, {Vec3(50, 0, 10.5), up}, near), InvalidArgument);
}

TEST(CrossSection, OpenSurfaceGivesAnOpenChain) {
  // A vessel with an unsutured incision: a 300-degree cylindrical panel (axis along y).
  CylinderPanelParams cp;
  cp.radius = kR;
  cp.length = 20.0;
  cp.angle_start_deg = -150.0;
  cp.angle_end_deg = 150.0;
  cp.segments_around = 25;
  cp.segments_along = 20;
  const SurfaceMesh m = make_cylinder_panel(cp);
  const CrossSection cs = cross_section(m, {Vec3(0, 10.5, 0), Vec3(0, 1, 0)});
  EXPECT_FALSE(cs.closed);
  ASSERT_GE(cs.points.size(), 2u);
  const double chord = 2.0 * kR * std::sin(0.5 * (300.0 / 25) * kPi / 180.0);
  EXPECT_NEAR(cs.perimeter, 25 * chord, 1e-12 * kR);  // no closing segment
  EXPECT_NEAR((cs.points.front() - cs.points.back()).norm(), 2.0 * kR * std::sin(30.0 * kPi / 180.0),
              1e-12 * kR);
  // The area closes the chain with the chord across the 60-degree gap: 25 central triangles
  // of 12 degrees plus the central triangle of the gap.
  const double expected = 12.5 * kR * kR * std::sin(12.0 * kPi / 180.0) +
                          0.5 * kR * kR * std::sin(60.0 * kPi / 180.0);
  EXPECT_NEAR(cs.area, expected, 1e-12 * expected);
}

TEST(CrossSection, FlatStripGivesAnOpenSegment) {
  const SurfaceMesh m = make_strip({40.0, 10.0, 40, 10});
  const CrossSection cs = cross_section(m, {Vec3(10.5, 0, 0), Vec3(1, 0, 0)});
  EXPECT_FALSE(cs.closed);
  EXPECT_NEAR(cs.perimeter, 10.0, 1e-12);
  EXPECT_NEAR(cs.max_diameter, 10.0, 1e-12);
  EXPECT_EQ(cs.min_diameter, 0.0);
  EXPECT_EQ(cs.area, 0.0);
}

TEST(CrossSection, InvalidInputsThrow) {
  const SurfaceMesh m = tube();
  EXPECT_THROW((void)cross_section(m, {Vec3(0, 0, 10), Vec3::Zero()}), InvalidArgument);
  EXPECT_THROW((void)cross_section(m, {Vec3(0, 0, 10), Vec3(0, 0, NAN)}), InvalidArgument);
  EXPECT_THROW((void)cross_section(m, {Vec3(0, 0, 50), Vec3(0, 0, 1)}), InvalidArgument);
  CrossSectionParams bad;
  bad.max_radius = 0.0;
  EXPECT_THROW((void)cross_section(m, {Vec3(0, 0, 10), Vec3(0, 0, 1)}, bad), InvalidArgument);
  const std::vector<Vec3> p = {Vec3(0, 0, -1), Vec3(1, 0, 1), Vec3(0, 1, 1)};
  const std::vector<FaceIndices> out_of_range = {{0, 1, 3}};
  EXPECT_THROW((void)cross_section(p, out_of_range, {Vec3::Zero(), Vec3(0, 0, 1)}), InvalidArgument);
}

TEST(LumenProfile, FindsTheNarrowedStation) {
  // Radius scaled by f(z) = 1 - 0.4 exp(-((z - 27.5) / 3)^2): narrowest at z = 27.5, which is
  // station 5 of 8 (stations at z = 2.5, 7.5, ..., 37.5). The scaling is symmetric about 27.5,
  // so rings 27 and 28 have the same radius r and the section there is A_n (r / R)^2 exactly.
  const auto f = [](double z) { return 1.0 - 0.4 * std::exp(-std::pow((z - 27.5) / 3.0, 2)); };
  const SurfaceMesh m = scaled(tube(), [&](const Vec3& p) {
    return Vec3(p.x() * f(p.z()), p.y() * f(p.z()), p.z());
  });
  LumenProfileParams params;
  params.stations = 8;
  const LumenProfile prof =
      lumen_profile(m, {Vec3(0, 0, 0), Vec3(0, 0, 20), Vec3(0, 0, 40)}, params);
  ASSERT_EQ(prof.stations.size(), 8u);
  ASSERT_TRUE(prof.min_area_station.has_value());
  EXPECT_EQ(*prof.min_area_station, 5u);
  const LumenStation& s = prof.stations[5];
  EXPECT_DOUBLE_EQ(s.arc_length, 27.5);
  EXPECT_NEAR((s.plane.normal - Vec3(0, 0, 1)).norm(), 0.0, 1e-15);
  ASSERT_TRUE(s.section.has_value());
  EXPECT_NEAR(s.section->area, ngon_area() * f(27.0) * f(27.0), 1e-12 * ngon_area());
  for (const auto& st : prof.stations) ASSERT_TRUE(st.section && st.section->closed);
}

TEST(LumenProfile, StationsOutsideTheVesselHaveNoSection) {
  const SurfaceMesh m = tube();  // z in [0, 40]; the centreline runs on to z = 80
  LumenProfileParams params;
  params.stations = 4;  // z = 10, 30, 50, 70
  const LumenProfile prof = lumen_profile(m, {Vec3(0, 0, 0), Vec3(0, 0, 80)}, params);
  EXPECT_TRUE(prof.stations[1].section.has_value());
  EXPECT_FALSE(prof.stations[2].section.has_value());
  EXPECT_FALSE(prof.stations[3].section.has_value());
  EXPECT_THROW((void)lumen_profile(m, {Vec3(0, 0, 0)}), InvalidArgument);
  EXPECT_THROW((void)lumen_profile(m, {Vec3(0, 0, 0), Vec3(0, 0, 0)}), InvalidArgument);
  params.stations = 0;
  EXPECT_THROW((void)lumen_profile(m, {Vec3(0, 0, 0), Vec3(0, 0, 1)}, params), InvalidArgument);
}

TEST(VertexFields, DisplacementMagnitude) {
  const std::vector<Vec3> a = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
  const std::vector<Vec3> b = {Vec3(3, 4, 0), Vec3(1, 1, 1)};
  EXPECT_EQ(displacement_magnitude(a, b), (std::vector<double>{5.0, 0.0}));
  EXPECT_THROW((void)displacement_magnitude(a, std::vector<Vec3>{Vec3::Zero()}), InvalidArgument);
}

TEST(VertexFields, FaceToVertexIsAreaWeighted) {
  // Face 0 has area 1, face 1 area 3; vertices 0 and 2 are shared.
  const SurfaceMesh m({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 3, 0)}, {{0, 1, 2}, {0, 2, 3}});
  const std::vector<double> per_face = {1.0, 5.0};
  EXPECT_EQ(face_to_vertex(m, per_face), (std::vector<double>{4.0, 1.0, 4.0, 5.0}));
  ElementMeasures em;
  em.membrane_strain = per_face;
  em.bending_curvature = {2.0, 2.0};
  em.energy_density = {0.0, 4.0};
  const VertexMeasures vm = face_to_vertex(m, em);
  EXPECT_EQ(vm.membrane_strain, (std::vector<double>{4.0, 1.0, 4.0, 5.0}));
  EXPECT_EQ(vm.bending_curvature, (std::vector<double>{2.0, 2.0, 2.0, 2.0}));
  EXPECT_EQ(vm.energy_density, (std::vector<double>{3.0, 0.0, 3.0, 4.0}));
  EXPECT_THROW((void)face_to_vertex(m, std::vector<double>{1.0}), InvalidArgument);
}
