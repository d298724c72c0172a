#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/sim/loads.hpp"

using namespace sutura::engine;

namespace {

// A small curved patch: 3x3 grid bent into a saddle, as flat arrays plus per-element rest.
struct Patch {
  std::vector<FaceIndices> faces;
  RestState rest;
  std::vector<ShellMaterial> materials{ShellMaterial{}};
  std::vector<int> face_material;
  ShellState state;
  ShellProblem problem() const {
    return ShellProblem{&faces, &rest, &materials, &face_material, state.x.size()};
  }
};

Patch make_patch() {
  Patch p;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const double x = i, y = j;
      p.state.x.emplace_back(x, y, 0.1 * (x - 1) * (x - 1) - 0.15 * (y - 1) * (y - 1));
      p.state.D.push_back(Quat::Identity());
    }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = j * 3 + i, b = a + 1, c = a + 4, d = a + 3;
      p.faces.push_back({a, b, c});
      p.faces.push_back({a, c, d});
    }
  for (const auto& f : p.faces) {
    ElementRest e;
    for (int k = 0; k < 3; ++k) {
      e.X[k] = p.state.x[f[k]];
      e.Q[k] = Quat::Identity();
    }
    p.rest.elements.push_back(e);
  }
  p.face_material.assign(p.faces.size(), 0);
  return p;
}

}  // namespace

TEST(Loads, NodalForcesMomentsAndScaling) {
  Patch p = make_patch();
  Loads l;
  l.nodal.push_back({4, Vec3(1, 2, 3), Vec3(0, 0, 5)});
  Eigen::VectorXd f;
  external_forces(p.problem(), p.state, l, 0.5, 6, f, nullptr);
  EXPECT_EQ(f.size(), 9 * 6);
  EXPECT_DOUBLE_EQ(f[4 * 6 + 2], 1.5);
  EXPECT_DOUBLE_EQ(f[4 * 6 + 5], 2.5);
  EXPECT_DOUBLE_EQ(f.sum(), 0.5 * (1 + 2 + 3 + 5));
  EXPECT_THROW(external_forces(p.problem(), p.state, l, 1.0, 3, f, nullptr), InvalidArgument);
}

TEST(Loads, BodyForceTotalsRestArea) {
  Patch p = make_patch();
  double area = 0.0;
  for (const auto& e : p.rest.elements) area += 0.5 * (e.X[1] - e.X[0]).cross(e.X[2] - e.X[0]).norm();
  Loads l;
  l.body_force_per_area = Vec3(0, 0, -90);
  Eigen::VectorXd f;
  external_forces(p.problem(), p.state, l, 1.0, 3, f, nullptr);
  double fz = 0.0;
  for (int n = 0; n < 9; ++n) fz += f[n * 3 + 2];
  EXPECT_NEAR(fz, -90.0 * area, 1e-10 * 90.0 * area);
}

TEST(Loads, LineLoadLumpsTotalByLength) {
  std::vector<Vec3> pos = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0)};
  auto nodal = lump_line_load(pos, {VertexId(0), VertexId(1), VertexId(2)}, Vec3(0, 0, 2));
  ASSERT_EQ(nodal.size(), 3u);
  EXPECT_DOUBLE_EQ(nodal[0].force.z(), 1.0);  // half of segment 1 (length 1)
  EXPECT_DOUBLE_EQ(nodal[1].force.z(), 3.0);  // halves of both segments
  EXPECT_DOUBLE_EQ(nodal[2].force.z(), 2.0);
  EXPECT_THROW(lump_line_load(pos, {VertexId(0)}, Vec3(0, 0, 1)), InvalidArgument);
}

TEST(Loads, PressureResultantAndLoadStiffnessMatchFiniteDifferences) {
  Patch p = make_patch();
  Loads l;
  l.pressures.push_back({{}, 0.7});
  Eigen::VectorXd f;
  Triplets K;
  external_forces(p.problem(), p.state, l, 1.0, 3, f, &K);
  // Resultant: p * sum of area vectors.
  Vec3 total = Vec3::Zero(), expect = Vec3::Zero();
  for (int n = 0; n < 9; ++n) total += f.segment<3>(n * 3);
  for (const auto& fc : p.faces)
    expect += 0.5 * 0.7 * (p.state.x[fc[1]] - p.state.x[fc[0]]).cross(p.state.x[fc[2]] - p.state.x[fc[0]]);
  EXPECT_LT((total - expect).norm(), 1e-12);

  Eigen::SparseMatrix<double> Ks(27, 27);
  Ks.setFromTriplets(K.begin(), K.end());
  Eigen::MatrixXd J(27, 27);
  const double h = 1e-6;
  for (int c = 0; c < 27; ++c) {
    ShellState sp = p.state, sm = p.state;
    sp.x[c / 3][c % 3] += h;
    sm.x[c / 3][c % 3] -= h;
    Eigen::VectorXd fp, fm;
    external_forces(p.problem(), sp, l, 1.0, 3, fp, nullptr);
    external_forces(p.problem(), sm, l, 1.0, 3, fm, nullptr);
    J.col(c) = (fp - fm) / (2 * h);
  }
  const Eigen::MatrixXd expected = -0.5 * (J + J.transpose());
  EXPECT_LT((Eigen::MatrixXd(Ks) - expected).norm(), 1e-7 * expected.norm());
}

// The pressure work is the potential of the pressure forces wherever a vertex's faces are all
// pressurised: d W(s0 -> s0 + a v) / da = f_ext(s0 + a v) . v for a move v of the centre vertex
// of the patch (its one-ring is the whole patch), at any a, not only to first order.
TEST(Loads, PressureWorkIsThePotentialOfThePressureForcesAtInteriorVertices) {
  Patch p = make_patch();
  Loads l;
  l.pressures.push_back({{}, 0.7});
  const Vec3 v(0.3, -0.2, 0.9);
  const auto moved = [&](double a) {
    ShellState s = p.state;
    s.x[4] += a * v;
    return s;
  };
  for (const double a : {0.0, 0.4, 1.3}) {
    const double h = 1e-5;
    const double dw = (load_work(p.problem(), p.state, moved(a + h), l, 2.0) -
                       load_work(p.problem(), p.state, moved(a - h), l, 2.0)) /
                      (2 * h);
    Eigen::VectorXd f;
    external_forces(p.problem(), moved(a), l, 2.0, 3, f, nullptr);
    const double expected = f.segment<3>(4 * 3).dot(v);
    EXPECT_NEAR(dw, expected, 1e-8 * std::abs(expected)) << "a = " << a;
  }
  // No move, no work; the work of a move and of its reverse cancel.
  EXPECT_EQ(load_work(p.problem(), p.state, p.state, l, 1.0), 0.0);
  EXPECT_NEAR(load_work(p.problem(), p.state, moved(0.5), l, 1.0),
              -load_work(p.problem(), moved(0.5), p.state, l, 1.0), 1e-15);
}

TEST(Loads, DeadLoadWorkIsForceTimesDisplacementAndMomentTimesRotation) {
  Patch p = make_patch();
  Loads l;
  l.nodal.push_back({2, Vec3(1.0, -2.0, 0.5), Vec3(0.0, 0.0, 3.0)});
  l.body_force_per_area = Vec3(0.0, 0.0, -0.25);
  ShellState to = p.state;
  const Vec3 shift(0.1, 0.2, -0.3);
  for (auto& x : to.x) x += shift;  // a rigid translation of everything
  to.D[2] = Quat(Eigen::AngleAxisd(0.6, Vec3(0.0, 0.6, 0.8)));
  double area = 0.0;
  for (const auto& e : p.rest.elements) area += rest_area(e);
  const double expected = 1.5 * (Vec3(1.0, -2.0, 0.5).dot(shift) + 3.0 * 0.8 * 0.6 +
                                 area * Vec3(0.0, 0.0, -0.25).dot(shift));
  EXPECT_NEAR(load_work(p.problem(), p.state, to, l, 1.5), expected, 1e-12);
  ShellState wrong = p.state;
  wrong.x.pop_back();
  EXPECT_THROW(load_work(p.problem(), p.state, wrong, l, 1.0), InvalidArgument);
}

namespace {

// A tube (radius 4, length 6, 12 x 3 segments) as a problem for free_pressure_rim: its two end
// loops are open rims, z = 0 and z = 6.
struct Tube {
  SurfaceMesh mesh = make_tube({4.0, 6.0, 12, 3});
  std::vector<FaceIndices> faces = mesh.faces();
  ShellState state = state_from_mesh(mesh);
  RestState rest = rest_from_state(mesh, state);
  std::vector<ShellMaterial> materials{ShellMaterial{}};
  std::vector<int> face_material = std::vector<int>(faces.size(), 0);
  [[nodiscard]] ShellProblem problem() const {
    return ShellProblem{&faces, &rest, &materials, &face_material, mesh.num_vertices()};
  }
  // Vertices within 1e-9 of the plane z = `z`, sorted.
  [[nodiscard]] std::vector<std::size_t> ring(double z) const {
    std::vector<std::size_t> out;
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
      if (std::abs(mesh.positions()[v].z() - z) < 1e-9) out.push_back(v);
    return out;
  }
  // The faces with every corner at z <= `z`.
  [[nodiscard]] std::vector<FaceId> faces_below(double z) const {
    std::vector<FaceId> out;
    for (std::size_t e = 0; e < faces.size(); ++e) {
      bool below = true;
      for (int k = 0; k < 3; ++k) below = below && mesh.positions()[faces[e][k]].z() <= z + 1e-9;
      if (below) out.emplace_back(static_cast<int>(e));
    }
    return out;
  }
};

std::vector<std::size_t> joined(std::vector<std::size_t> a, const std::vector<std::size_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  return a;
}

}  // namespace

// The rim of a pressure is where the pressure forces are not the derivative of load_work: at
// every vertex free_pressure_rim names, moving the vertex does work other than its force, and
// at every other vertex exactly its force (pressure on the lower two thirds of an open tube:
// the rims are the open end z = 0 and the border of the pressurised part, z = 4).
TEST(Loads, FreePressureRimIsWhereThePressureForcesHaveNoPotential) {
  Tube t;
  Loads l;
  l.pressures.push_back({t.faces_below(4.0), 0.3});
  const std::vector<std::size_t> rim = free_pressure_rim(t.problem(), l, Constraints{});
  EXPECT_EQ(rim, joined(t.ring(0.0), t.ring(4.0)));
  Eigen::VectorXd f;
  external_forces(t.problem(), t.state, l, 1.0, 3, f, nullptr);
  const Vec3 v(0.3, -0.5, 0.8);
  for (std::size_t n = 0; n < t.mesh.num_vertices(); ++n) {
    const auto moved = [&](double a) {
      ShellState s = t.state;
      s.x[n] += a * v;
      return s;
    };
    const double h = 1e-2;  // load_work is linear in one vertex's position: no truncation
    const double dw = (load_work(t.problem(), t.state, moved(h), l, 1.0) -
                       load_work(t.problem(), t.state, moved(-h), l, 1.0)) /
                      (2 * h);
    const double force = f.segment<3>(3 * n).dot(v);
    const bool on_rim = std::binary_search(rim.begin(), rim.end(), n);
    if (on_rim) EXPECT_GT(std::abs(dw - force), 1e-3 * std::abs(force) + 1e-9) << "vertex " << n;
    else EXPECT_NEAR(dw, force, 1e-8 * (std::abs(force) + 1e-3)) << "vertex " << n;
  }
}

// Held rims do not count (all three translations held, rotations need not be); a rim held in
// only two translations does. Equal pressures from two loads on the same faces cancel across
// every inner edge; two different pressures meeting make a rim; so does a face turned over.
TEST(Loads, FreePressureRimIgnoresHeldVerticesAndFindsPressureJumpsAndFlippedFaces) {
  Tube t;
  const std::size_t n = t.mesh.num_vertices();
  const auto ends = joined(t.ring(0.0), t.ring(6.0));
  const auto ids = [](const std::vector<std::size_t>& vs) {
    std::vector<VertexId> out;
    for (const std::size_t v : vs) out.emplace_back(static_cast<int>(v));
    return out;
  };
  Loads uniform;
  uniform.pressures.push_back({{}, 0.3});
  EXPECT_EQ(free_pressure_rim(t.problem(), uniform, Constraints{}), ends);
  Constraints held;
  held.fix(ids(ends), kTranslations, n);
  EXPECT_TRUE(free_pressure_rim(t.problem(), uniform, held).empty());
  Constraints partly;
  partly.fix(ids(ends), kUx | kUy | kRotations, n);
  EXPECT_EQ(free_pressure_rim(t.problem(), uniform, partly), ends);

  Loads twice = uniform;
  twice.pressures.push_back({{}, 0.1});
  EXPECT_TRUE(free_pressure_rim(t.problem(), twice, held).empty());
  Loads stepped = uniform;
  stepped.pressures.push_back({t.faces_below(2.0), 0.1});
  EXPECT_EQ(free_pressure_rim(t.problem(), stepped, held), t.ring(2.0));
  Loads nothing;
  nothing.pressures.push_back({{}, 0.0});
  EXPECT_TRUE(free_pressure_rim(t.problem(), nothing, Constraints{}).empty());

  // A face in the middle turned over (two corners swapped): its normal, and its pressure,
  // point the other way.
  const FaceId middle = t.faces_below(4.0).back();
  std::swap(t.faces[middle.index()][1], t.faces[middle.index()][2]);
  std::vector<std::size_t> corners(t.faces[middle.index()].begin(), t.faces[middle.index()].end());
  std::sort(corners.begin(), corners.end());
  EXPECT_EQ(free_pressure_rim(t.problem(), uniform, held), corners);
}
