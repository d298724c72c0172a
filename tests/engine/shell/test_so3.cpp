// The rotation-group helpers of the 6-DOF shell (engine/src/shell/so3.hpp): the logarithm's
// small-angle series against the closed form, and J_l^{-1} against its defining property.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "so3.hpp"

namespace sutura::engine {
namespace {

using so3::Mat3;
using so3::Quat;
using so3::Vec3;

// Rotation vector of a quaternion by the closed form alone (the reference for the series).
Vec3 log_closed_form(const Quat& q_in) {
  const Quat q = q_in.w() < 0.0 ? Quat(-q_in.coeffs()) : q_in;
  const double s = q.vec().norm();
  return (2.0 * std::atan2(s, q.w()) / s) * q.vec();
}

TEST(So3, LogInvertsExpOnBothSidesOfTheSeriesBranch) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Angles from 1e-9 rad to pi - 1e-6 rad; the series branch ends at 2 atan(0.1) = 0.1993 rad.
  for (const double angle : {1e-9, 1e-5, 0.01, 0.1, 0.19, 0.1993, 0.1994, 0.21, 1.0, 3.0,
                             std::numbers::pi - 1e-6}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 theta = angle * axis;
      const Vec3 back = so3::log_quat(so3::exp_quat(theta));
      // exp then log loses a few ulps of the angle (the quaternion is rounded).
      EXPECT_LE((back - theta).norm(), 4e-16 * std::max(1.0, angle)) << "angle " << angle;
    }
  }
}

TEST(So3, LogSeriesAgreesWithTheClosedFormToRoundOff) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    // Up to 0.25 rad, past the end of the series branch; also slightly non-unit quaternions,
    // as products of rounded unit quaternions are.
    const double angle = 0.25 * std::abs(u(rng));
    const Quat q = so3::exp_quat(angle * Vec3(u(rng), u(rng), u(rng)).normalized());
    const Quat scaled(q.coeffs() * (1.0 + 1e-15 * u(rng)));
    const Vec3 series = so3::log_quat(scaled), closed = log_closed_form(scaled);
    // Each side rounds about four times (its factor k and the product k v) by at most half
    // an ulp (1.1e-16 relative): the two may differ by 1e-15 relative, not by truncation.
    EXPECT_LE((series - closed).norm(), 1e-15 * closed.norm()) << "angle " << angle;
  }
}

TEST(So3, LeftJacobianInverseMapsSpinsToRotationVectorRates) {
  // exp(theta + J_l^{-1} phi eps) = exp(phi eps) exp(theta) to first order: checked by central
  // differences of log(exp(phi eps) exp(theta)) on both branches of eta (t < 0.25 and above).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const double angle : {0.0, 0.1, 0.24, 0.26, 1.0, 2.5}) {
    const Vec3 theta = angle * Vec3(u(rng), u(rng), u(rng)).normalized();
    const Mat3 H = so3::left_jacobian_inverse(theta);
    const double eps = 1e-6;
    for (int k = 0; k < 3; ++k) {
      const Vec3 phi = Vec3::Unit(k);
      const Vec3 plus = so3::log_quat(so3::exp_quat(eps * phi) * so3::exp_quat(theta));
      const Vec3 minus = so3::log_quat(so3::exp_quat(-eps * phi) * so3::exp_quat(theta));
      const Vec3 rate = (plus - minus) / (2.0 * eps);
      EXPECT_LE((rate - H.col(k)).norm(), 1e-8) << "angle " << angle << ", spin axis " << k;
    }
    // The gradient's matrix-free product H^T m agrees with the matrix to round-off.
    const Vec3 m(u(rng), u(rng), u(rng));
    const Vec3 product = so3::left_jacobian_inverse_transpose_times(theta, m);
    EXPECT_LE((product - H.transpose() * m).norm(), 1e-15 * (1.0 + angle) * m.norm())
        << "angle " << angle;
  }
}

}  // namespace
}  // namespace sutura::engine
