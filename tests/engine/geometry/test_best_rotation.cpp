// The Procrustes rotation (best_rotation.hpp): by SVD, and by Newton's method from an estimate.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "best_rotation.hpp"

namespace sutura::engine::detail {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d rotation(const Vector3d& axis_angle) {
  const double a = axis_angle.norm();
  return a == 0.0 ? Matrix3d::Identity()
                  : Eigen::AngleAxisd(a, axis_angle / a).toRotationMatrix();
}

// S = sum_k a_k b_k^T for edges a_k moved by R and then deformed by `strain` (b = R F a).
Matrix3d covariance(std::mt19937& rng, const Matrix3d& R, double strain, bool planar) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Matrix3d F = Matrix3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) F(r, c) += strain * u(rng);
  Matrix3d S = Matrix3d::Zero();
  for (int k = 0; k < 6; ++k) {
    const Vector3d a(u(rng), u(rng), planar ? 0.0 : u(rng));
    S += a * (R * F * a).transpose();
  }
  return S;
}

double objective(const Matrix3d& S, const Matrix3d& R) { return (R * S).trace(); }

TEST(BestRotation, RecoversTheRotationOfRigidlyMovedEdgesAlsoWhenTheyArePlanar) {
  std::mt19937 rng(7);
  for (const bool planar : {false, true}) {
    const Matrix3d R = rotation(Vector3d(1.1, -2.0, 0.4));
    const Matrix3d Q = best_rotation(covariance(rng, R, 0.0, planar));
    EXPECT_LT((Q - R).norm(), 1e-12);
    EXPECT_NEAR(Q.determinant(), 1.0, 1e-12);
  }
  EXPECT_EQ(best_rotation(Matrix3d::Zero()), Matrix3d::Identity());
}

// Where the best orthogonal map is a reflection, the best proper rotation: for
// S = diag(3, 2, -1) the identity (tr(R S) = 4; a half turn about x gives 2).
TEST(BestRotation, AvoidsTheReflection) {
  const Matrix3d S = Vector3d(3.0, 2.0, -1.0).asDiagonal();
  EXPECT_LT((best_rotation(S) - Matrix3d::Identity()).norm(), 1e-14);
  Matrix3d R = rotation(Vector3d(0.2, -0.1, 0.3));
  ASSERT_TRUE(refine_best_rotation(S, R));
  EXPECT_LT((R - Matrix3d::Identity()).norm(), 1e-12);
}

// From an estimate within 0.3 rad (a time step apart is far closer), Newton converges to the
// SVD's rotation, for solid and planar edge sets, rigid or strained by up to 30 %.
TEST(BestRotation, NewtonFromANearbyRotationConvergesToTheSvdAnswer) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int cases = 0;
  for (const bool planar : {false, true})
    for (const double strain : {0.0, 0.1, 0.3})
      for (int trial = 0; trial < 50; ++trial) {
        const Matrix3d S = covariance(rng, rotation(3.0 * Vector3d(u(rng), u(rng), u(rng))),
                                      strain, planar);
        const Matrix3d best = best_rotation(S);
        Matrix3d R = best * rotation(0.3 / std::sqrt(3.0) * Vector3d(u(rng), u(rng), u(rng)));
        ASSERT_TRUE(refine_best_rotation(S, R)) << "planar " << planar << " strain " << strain;
        EXPECT_LT((R - best).norm(), 1e-12);
        EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
        ++cases;
      }
  EXPECT_EQ(cases, 300);
}

// From any estimate, Newton either finds the maximum of tr(R S) or says it did not (then
// best_rotation is used): it never returns another stationary point.
TEST(BestRotation, NewtonNeverReturnsAnotherRotation) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int converged = 0, declined = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Matrix3d S = covariance(rng, rotation(3.0 * Vector3d(u(rng), u(rng), u(rng))), 0.2,
                                  trial % 2 == 0);
    const Matrix3d best = best_rotation(S);
    // Half the estimates near a half turn from the answer, where the saddles are.
    const double reach = trial % 4 < 2 ? 3.1 : 1.5;
    Matrix3d R = best * rotation(reach / std::sqrt(3.0) * Vector3d(u(rng), u(rng), u(rng)));
    if (refine_best_rotation(S, R)) {
      EXPECT_LT((R - best).norm(), 1e-10);
      EXPECT_GE(objective(S, R), objective(S, best) - 1e-12 * S.norm());
      ++converged;
    } else {
      ++declined;
    }
  }
  EXPECT_GT(converged, 0);
  EXPECT_GT(declined, 0);
  // Started at a saddle, a half turn about a singular axis from the answer: declined.
  const Matrix3d D = Vector3d(3.0, 2.0, 1.0).asDiagonal();
  Matrix3d half = rotation(Vector3d(M_PI, 0.0, 0.0));
  EXPECT_FALSE(refine_best_rotation(D, half));
  // Edges along one line leave the turn about it free: declined.
  const Vector3d a(1.0, 2.0, -0.5);
  Matrix3d R = Matrix3d::Identity();
  EXPECT_FALSE(refine_best_rotation(a * a.transpose(), R));
}

}  // namespace
}  // namespace sutura::engine::detail
