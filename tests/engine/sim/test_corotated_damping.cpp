// The nodes' rotations (nodal_rotations.hpp) and the corotated stiffness damping built on them
// (corotated_damping.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "corotated_damping.hpp"
#include "nodal_rotations.hpp"
#include "sim_fixture.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

using testing::Cantilever;

Eigen::Matrix3d rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

std::vector<Vec3> moved(const std::vector<Vec3>& x, const Eigen::Matrix3d& R, const Vec3& t) {
  std::vector<Vec3> out;
  for (const Vec3& p : x) out.push_back(R * p + t);
  return out;
}

TEST(NodalRotations, RigidMotionGivesItsRotationAtEveryNode) {
  const SurfaceMesh tube = make_tube({4.0, 10.0, 12, 6});
  const detail::NodalRotations rings(tube.faces(), tube.num_vertices());
  const Eigen::Matrix3d R = rotation(2.5, Vec3(1, -2, 0.5));  // far beyond small angles
  std::vector<Eigen::Matrix3d> Q;
  EXPECT_LT(rings.compute(tube.positions(), moved(tube.positions(), R, Vec3(3, -1, 7)), Q), 1e-6);
  ASSERT_EQ(Q.size(), tube.num_vertices());
  for (const auto& q : Q) EXPECT_LT((q - R).norm(), 1e-12);
  rings.compute(tube.positions(), tube.positions(), Q);
  for (const auto& q : Q) EXPECT_LT((q - Eigen::Matrix3d::Identity()).norm(), 1e-14);
}

// Planar one-rings (a flat strip) still give a proper rotation: the normal is taken along.
TEST(NodalRotations, FlatOneRingsGiveProperRotations) {
  const SurfaceMesh strip = make_strip({10.0, 1.0, 10, 2});
  const detail::NodalRotations rings(strip.faces(), strip.num_vertices());
  const Eigen::Matrix3d R = rotation(-1.2, Vec3(0.3, 1, 0.2));
  std::vector<Eigen::Matrix3d> Q;
  rings.compute(strip.positions(), moved(strip.positions(), R, Vec3::Zero()), Q);
  for (const auto& q : Q) {
    EXPECT_NEAR(q.determinant(), 1.0, 1e-12);
    EXPECT_LT((q - R).norm(), 1e-12);
  }
}

// A strip (10 x 1, ten segments along) rolled into an arc of one radian: each node turns
// with the arc's tangent, and the bend returned is about the turn from one column of nodes
// to the next, 0.1 rad.
TEST(NodalRotations, BendIsTheTurnBetweenNeighbouringNodes) {
  const SurfaceMesh strip = make_strip({10.0, 1.0, 10, 2});
  const detail::NodalRotations rings(strip.faces(), strip.num_vertices());
  const double radius = 10.0;
  std::vector<Vec3> rolled;
  for (const Vec3& p : strip.positions()) {
    const double a = p.x() / radius;
    rolled.emplace_back(radius * std::sin(a), p.y(), radius * (1.0 - std::cos(a)));
  }
  std::vector<Eigen::Matrix3d> Q;
  const double bend = rings.compute(strip.positions(), rolled, Q);
  EXPECT_GE(bend, 0.09);  // 0.1 between columns, a little more where the end nodes'
  EXPECT_LE(bend, 0.15);  // one-sided rings are fitted half a segment off
  for (std::size_t i = 0; i < Q.size(); ++i) {
    // Turned about -y by about the arc angle at the node (one-sided rings at the ends).
    const double angle = std::atan2(-Q[i](0, 2), Q[i](0, 0));
    EXPECT_NEAR(angle, strip.position(VertexId(static_cast<std::int32_t>(i))).x() / radius, 0.06);
  }
}

// Warm-started from the last result (Newton, refine_best_rotation), the rotations are the
// ones computed from scratch (SVD), for a tube turned and bent a little further.
TEST(NodalRotations, WarmStartGivesTheRotationsComputedFromScratch) {
  const SurfaceMesh tube = make_tube({4.0, 10.0, 12, 6});
  const detail::NodalRotations rings(tube.faces(), tube.num_vertices());
  const auto bent = [&](double a) {
    std::vector<Vec3> out;
    for (const Vec3& p : tube.positions())
      out.push_back(rotation(a * p.z() / 10.0, Vec3(1, 0, 0)) * p);  // twisted and bent along z
    return moved(out, rotation(a, Vec3(0.3, 1, -0.2)), Vec3::Zero());
  };
  std::vector<Eigen::Matrix3d> warm, cold;
  rings.compute(tube.positions(), bent(0.2), warm);
  const double bend_warm = rings.compute(tube.positions(), bent(0.21), warm);
  const double bend_cold = rings.compute(tube.positions(), bent(0.21), cold);
  ASSERT_EQ(warm.size(), cold.size());
  for (std::size_t i = 0; i < warm.size(); ++i) EXPECT_LT((warm[i] - cold[i]).norm(), 1e-12);
  EXPECT_NEAR(bend_warm, bend_cold, 1e-12);
  EXPECT_GT(bend_cold, 0.0);
}

TEST(NodalRotations, NodeInNoFaceKeepsTheIdentityAndBadInputThrows) {
  const std::vector<FaceIndices> faces{{0, 1, 2}};
  const detail::NodalRotations rings(faces, 4);
  const std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 5, 5)};
  std::vector<Eigen::Matrix3d> Q;
  rings.compute(x, moved(x, rotation(0.7, Vec3(0, 0, 1)), Vec3::Zero()), Q);
  EXPECT_EQ(Q[3], Eigen::Matrix3d::Identity());
  EXPECT_THROW(detail::NodalRotations(faces, 2), InvalidArgument);
  EXPECT_THROW(rings.compute(x, {x[0]}, Q), InvalidArgument);
}

// Turned with a rigid rotation R of the shell since its stiffness was taken, the damping
// force of a velocity field is the force of the unturned field, turned: R K (R^T v). A rigid
// rotation of the current shape (whose velocity K annihilates in the reference pose) is
// therefore not damped; matrix() is the operator apply() uses.
TEST(CorotatedDamping, TurnsTheStiffnessWithTheRotationOfTheShell) {
  Cantilever c(make_corotational_shell(), 0.0, 6, 2);
  const DofMap map(c.sys);
  const Evaluation ev = evaluate(c.sys, map, c.state, 1.0, true);
  detail::CorotatedDamping damping(c.sys, map);
  ASSERT_TRUE(damping.empty());
  damping.reset(ev.tangent, c.state.x);
  // The clamped root is held; every other node is free in all six DOFs.
  const Eigen::Matrix3d R = rotation(0.9, Vec3(0.2, 1, 0.4));
  damping.turn_to(moved(c.state.x, R, Vec3(0.5, 0, 0)));

  // An infinitesimal rigid rotation about the root of the turned pose: translations
  // omega x x_current, rotations omega.
  const Vec3 omega(0.3, -0.2, 0.5);
  Eigen::VectorXd v_full = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(c.sys.num_dofs()));
  for (std::size_t i = 0; i < c.state.x.size(); ++i) {
    v_full.segment<3>(6 * i) = omega.cross(R * c.state.x[i]);
    v_full.segment<3>(6 * i + 3) = omega;
  }
  const Eigen::VectorXd v = map.restrict(v_full);
  Eigen::VectorXd turned, plain;
  damping.apply(v, turned);
  plain = ev.tangent * v;
  const double scale = ev.tangent.norm() * v.norm();
  // Away from the held root the turned force vanishes: only the nodes sharing an element
  // with the root (at x = 10/6), which the held nodes pin, feel the rotation.
  EXPECT_GT(plain.norm(), 1e-3 * scale);  // unturned, the stiffness damps the rigid rotation
  Eigen::VectorXd interior = turned;
  for (std::size_t i = 0; i < c.state.x.size(); ++i) {
    if (c.state.x[i].x() > 2.0) continue;  // the root and the column of nodes next to it
    for (int k = 0; k < 6; ++k)
      if (const int f = map.full_to_free[6 * i + k]; f >= 0) interior[f] = 0.0;
  }
  EXPECT_LT(interior.norm(), 1e-12 * scale);

  // turn() applies Q node by node: here R to every free node's translation and rotation.
  Eigen::VectorXd along_x = Eigen::VectorXd::Zero(v.size());
  for (std::size_t i = 0; i < c.state.x.size(); ++i)
    if (const int f = map.full_to_free[6 * i]; f >= 0) along_x[f] = along_x[f + 4] = 1.0;
  Eigen::VectorXd t = along_x;
  damping.turn(false, t);
  for (std::size_t i = 0; i < c.state.x.size(); ++i)
    if (const int f = map.full_to_free[6 * i]; f >= 0) {
      EXPECT_LT((t.segment<3>(f) - R.col(0)).norm(), 1e-14);
      EXPECT_LT((t.segment<3>(f + 3) - R.col(1)).norm(), 1e-14);
    }
  damping.turn(true, t);
  EXPECT_LT((t - along_x).norm(), 1e-13);

  // matrix() is the operator of apply(), and afterwards apply() is unchanged.
  const Eigen::SparseMatrix<double> M = damping.matrix();
  EXPECT_FALSE(damping.turned());
  EXPECT_LT((M * v - turned).norm(), 1e-12 * scale);
  Eigen::VectorXd again;
  damping.apply(v, again);
  EXPECT_LT((again - turned).norm(), 1e-12 * scale);
}

}  // namespace
}  // namespace sutura::engine
