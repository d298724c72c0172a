// Tests of the per-element rest states (lerp, rest_from_state, element_frame), the state
// helpers and apply_increment. Tolerances are stated with each assertion.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "corotational_test_support.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {
namespace {

RestState random_rest(std::size_t elements, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  RestState r;
  r.elements.resize(elements);
  for (ElementRest& e : r.elements)
    for (int k = 0; k < 3; ++k) {
      e.X[k] = Vec3(u(rng), u(rng), u(rng));
      e.Q[k] = test::random_rotation(rng, 3.0);
    }
  return r;
}

double rotation_distance(const Quat& a, const Quat& b) { return a.angularDistance(b); }

TEST(RestState, LerpEndpointsEqualInputs) {
  const RestState a = random_rest(5, 1), b = random_rest(5, 2);
  const RestState r0 = lerp(a, b, 0.0), r1 = lerp(a, b, 1.0);
  for (std::size_t f = 0; f < 5; ++f)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(r0.elements[f].X[k], a.elements[f].X[k]);
      EXPECT_EQ(r1.elements[f].X[k], b.elements[f].X[k]);
      // Round-off of slerp and normalisation only.
      EXPECT_LT(rotation_distance(r0.elements[f].Q[k], a.elements[f].Q[k]), 1e-12);
      EXPECT_LT(rotation_distance(r1.elements[f].Q[k], b.elements[f].Q[k]), 1e-12);
    }
}

TEST(RestState, LerpMidpointAveragesPositionsAndHalvesRotations) {
  const RestState a = random_rest(4, 3), b = random_rest(4, 4);
  const RestState m = lerp(a, b, 0.5);
  for (std::size_t f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT((m.elements[f].X[k] - 0.5 * (a.elements[f].X[k] + b.elements[f].X[k])).norm(),
                1e-14);
      const Quat& qa = a.elements[f].Q[k];
      const Quat& qb = b.elements[f].Q[k];
      const Quat& qm = m.elements[f].Q[k];
      EXPECT_NEAR(qm.norm(), 1.0, 1e-15);
      // The midpoint of the shorter arc: equally far from both ends, half the total angle.
      const double total = rotation_distance(qa, qb);
      EXPECT_NEAR(rotation_distance(qa, qm), 0.5 * total, 1e-12);
      EXPECT_NEAR(rotation_distance(qm, qb), 0.5 * total, 1e-12);
    }
}

TEST(RestState, LerpRejectsDifferentSizes) {
  EXPECT_THROW((void)lerp(random_rest(3, 1), random_rest(4, 2), 0.5), InvalidArgument);
}

TEST(RestState, ElementFrameIsOrthonormalRightHandedWithNormalE3) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng)), p2(u(rng), u(rng), u(rng));
    const Eigen::Matrix3d T = element_frame(p0, p1, p2);
    EXPECT_LT((T.transpose() * T - Eigen::Matrix3d::Identity()).norm(), 1e-14);
    EXPECT_NEAR(T.determinant(), 1.0, 1e-14);
    const Vec3 n = (p1 - p0).cross(p2 - p0).normalized();
    EXPECT_LT((T.col(2) - n).norm(), 1e-14);
    EXPECT_LT((T.col(0) - (p1 - p0).normalized()).norm(), 1e-14);
  }
}

TEST(RestState, RestFromStateHoldsCornersAndTriadsInTheElementFrame) {
  const test::FlatArrays mesh = test::cylinder_panel(4.0, 1.0, 3.0, 3, 2);
  std::mt19937 rng(11);
  ShellState s = test::identity_state(mesh.x);
  for (Quat& q : s.D) q = test::random_rotation(rng, 3.0);
  const RestState r = rest_from_state(mesh.faces, s);
  ASSERT_EQ(r.elements.size(), mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const ElementRest& e = r.elements[f];
    const Eigen::Matrix3d T = element_frame(e.X[0], e.X[1], e.X[2]);
    for (int k = 0; k < 3; ++k) {
      const auto v = mesh.faces[f][k];
      EXPECT_EQ(e.X[k], s.x[v]);
      EXPECT_LT((e.Q[k].toRotationMatrix() - T.transpose() * s.D[v].toRotationMatrix()).norm(),
                1e-14);
    }
  }
}

TEST(RestState, RestFromStateOfAnyStateHasZeroEnergyAndGradient) {
  // A curved tube section (closed around) with random triads, and a random deformed state.
  const auto model = make_corotational_shell();
  const test::FlatArrays tube = test::tube(3.0, 6.0, 12, 4);
  std::mt19937 rng(13);
  ShellState s = test::identity_state(tube.x);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (Vec3& x : s.x) x += Vec3(u(rng), u(rng), u(rng));
  for (Quat& q : s.D) q = test::random_rotation(rng, 3.0);
  ShellMaterial m;
  test::ProblemSetup setup(tube, s, m);
  Eigen::VectorXd g;
  const double E = model->energy_gradient(setup.problem(), s, g);
  // Scales: force E t h ~ 1.6 N (h ~ 1.6 mm cells); round-off only.
  EXPECT_LT(std::abs(E), 1e-24);
  EXPECT_LT(g.lpNorm<Eigen::Infinity>(), 1e-12);
  // And the rest state of the undeformed mesh with identity triads (the paper's x0).
  ShellState s0 = test::identity_state(tube.x);
  test::ProblemSetup setup0(tube, s0, m);
  EXPECT_LT(std::abs(model->energy_gradient(setup0.problem(), s0, g)), 1e-24);
  EXPECT_LT(g.lpNorm<Eigen::Infinity>(), 1e-12);
}

TEST(RestState, StateFromMeshHasIdentityTriads) {
  const test::FlatArrays a = test::strip(2.0, 1.0, 2, 1);
  const SurfaceMesh mesh(a.x, a.faces);
  const ShellState s = state_from_mesh(mesh);
  ASSERT_EQ(s.x.size(), a.x.size());
  ASSERT_EQ(s.D.size(), a.x.size());
  for (std::size_t i = 0; i < a.x.size(); ++i) {
    EXPECT_EQ(s.x[i], a.x[i]);
    EXPECT_EQ(s.D[i].coeffs(), Quat::Identity().coeffs());
  }
  const RestState r = rest_from_state(mesh, s);
  EXPECT_EQ(r.elements.size(), a.faces.size());
}

TEST(ApplyIncrement, TranslatesAndRotatesWithTheExactExponential) {
  ShellState s;
  s.x = {Vec3(1.0, 2.0, 3.0), Vec3(-1.0, 0.0, 0.5)};
  const Quat D1(Eigen::AngleAxisd(0.7, Vec3(0.0, 1.0, 0.0)));
  s.D = {Quat::Identity(), D1};
  Eigen::VectorXd du(12);
  du << 0.1, 0.2, 0.3, 0.0, 0.0, 2.5,  //
      -0.5, 0.0, 1.0, 1.0, -2.0, 0.5;
  apply_increment(s, du, 6);
  EXPECT_LT((s.x[0] - Vec3(1.1, 2.2, 3.3)).norm(), 1e-15);
  EXPECT_LT((s.x[1] - Vec3(-1.5, 0.0, 1.5)).norm(), 1e-15);
  // Left (spatial) composition with the exact exponential, large angles included.
  EXPECT_LT(s.D[0].angularDistance(Quat(Eigen::AngleAxisd(2.5, Vec3::UnitZ()))), 1e-14);
  const Vec3 w(1.0, -2.0, 0.5);
  const Quat expected = Quat(Eigen::AngleAxisd(w.norm(), w.normalized())) * D1;
  EXPECT_LT(s.D[1].angularDistance(expected), 1e-14);
  EXPECT_NEAR(s.D[1].norm(), 1.0, 1e-15);
  // Tiny increments (series branch) compose consistently: 1000 steps of w/1000 = exp(w).
  ShellState t;
  t.x = {Vec3::Zero()};
  t.D = {Quat::Identity()};
  Eigen::VectorXd small(6);
  small << 0.0, 0.0, 0.0, 1e-5, 2e-5, -3e-5;
  for (int i = 0; i < 1000; ++i) apply_increment(t, small, 6);
  const Vec3 W = 1000.0 * small.tail<3>();
  EXPECT_LT(t.D[0].angularDistance(Quat(Eigen::AngleAxisd(W.norm(), W.normalized()))), 1e-13);
  // 3-DOF increments leave the triads alone.
  Eigen::VectorXd du3(6);
  du3 << 1.0, 0.0, 0.0, 0.0, 1.0, 0.0;
  const Quat before = s.D[1];
  apply_increment(s, du3, 3);
  EXPECT_EQ(s.D[1].coeffs(), before.coeffs());
  EXPECT_THROW(apply_increment(s, Eigen::VectorXd::Zero(5), 6), InvalidArgument);
  EXPECT_THROW(apply_increment(s, Eigen::VectorXd::Zero(8), 4), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
