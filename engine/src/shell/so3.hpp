#pragma once
// Rotation-group helpers for the 6-DOF shells (private to the engine; also the skew matrix
// that the loads, the collapse barrier and the hinge bending share).
//
// Conventions: rotation vectors theta (rad), R = exp([theta]x). Left (spatial) perturbations:
// exp(theta + dtheta) = exp([J_l(theta) dtheta]x) exp(theta), hence for R <- exp([phi]x) R the
// rotation vector changes by dtheta = J_l^{-1}(theta) phi. J_l^{-1} is the matrix called H
// in Felippa & Haugen (2005), "A unified formulation of small-strain corotational finite
// elements: I. Theory", CMAME 194 (rotation-vector Jacobian). Everything here is exact
// (no small-rotation approximation); series expansions replace the closed forms only where
// those lose precision (|theta| < 0.25).
// Cost: a few tens of flops each.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sutura::engine::so3 {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// [v]x: skew(v) * a = v x a.
inline Mat3 skew(const Vec3& v) {
  Mat3 s;
  s << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return s;
}

/// Exact exponential map as a unit quaternion: (cos(|w|/2), sin(|w|/2) w/|w|).
inline Quat exp_quat(const Vec3& w) {
  const double angle = w.norm();
  const double h = 0.5 * angle;
  // sin(h)/angle = 1/2 (1 - h^2/6 + h^4/120 - ...); series error < h^6/5040.
  const double k = angle < 1e-4 ? 0.5 * (1.0 - h * h / 6.0 + h * h * h * h / 120.0)
                                 : std::sin(h) / angle;
  return Quat(std::cos(h), k * w.x(), k * w.y(), k * w.z());
}

/// Rotation vector of a unit quaternion, |theta| <= pi (principal branch).
inline Vec3 log_quat(const Quat& q_in) {
  const Quat q = q_in.w() < 0.0 ? Quat(-q_in.coeffs()) : q_in;
  const Vec3 v = q.vec();
  const double s = v.norm();
  const double w = q.w();
  // 2 atan2(s, w)/s -> (2/w)(1 - s^2/(3 w^2)) for s -> 0 (w ~ 1 there).
  const double k = s < 1e-6 ? (2.0 / w) * (1.0 - s * s / (3.0 * w * w))
                            : 2.0 * std::atan2(s, w) / s;
  return k * v;
}

/// eta(t) = (1 - (t/2) cot(t/2)) / t^2 and mu(t) = eta'(t)/t, t = |theta|: the scalar
/// functions of J_l^{-1} and of its derivative.
struct InverseJacobianScalars {
  double eta;
  double mu;
};

inline InverseJacobianScalars inverse_jacobian_scalars(double t) {
  const double t2 = t * t;
  if (t < 0.25) {
    // (t/2) cot(t/2) = 1 - t^2/12 - t^4/720 - t^6/30240 - t^8/1209600 - t^10/47900160 - ...;
    // truncation error below 1e-10 relative here, where the closed forms lose up to 1e-7.
    return {1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0 + t2 * t2 * t2 / 1209600.0 +
                t2 * t2 * t2 * t2 / 47900160.0,
            1.0 / 360.0 + t2 / 7560.0 + t2 * t2 / 201600.0 + t2 * t2 * t2 / 5987520.0};
  }
  const double s = std::sin(t);
  const double c = std::cos(t);
  // (t/2) cot(t/2) = t (1 + c) / (2 s) = t s / (2 (1 - c)); the second form stays finite at t = pi.
  const double eta = 1.0 / t2 - s / (2.0 * t * (1.0 - c));
  // eta' = -2/t^3 + 1/(2t) + (s + t c) / (2 t^2 (1 - c))  (quotient rule, (1+c)/s^2 = 1/(1-c)).
  const double deta = -2.0 / (t2 * t) + 1.0 / (2.0 * t) + (s + t * c) / (2.0 * t2 * (1.0 - c));
  return {eta, deta / t};
}

/// J_l^{-1}(theta) = I - 1/2 [theta]x + eta [theta]x^2.
inline Mat3 left_jacobian_inverse(const Vec3& theta) {
  const Mat3 S = skew(theta);
  return Mat3::Identity() - 0.5 * S + inverse_jacobian_scalars(theta.norm()).eta * (S * S);
}

/// d/dtheta [J_l^{-T}(theta) m] for fixed m, with J_l^{-T} m = m + 1/2 theta x m
/// + eta (theta (theta.m) - t^2 m). The derivative gives the moment-correction stiffness
/// K_M of Felippa & Haugen (2005), Sec. 7.
inline Mat3 d_left_jacobian_inverse_transpose(const Vec3& theta, const Vec3& m) {
  const double t2 = theta.squaredNorm();
  const auto [eta, mu] = inverse_jacobian_scalars(std::sqrt(t2));
  const double tm = theta.dot(m);
  const Vec3 w = theta * tm - t2 * m;  // [theta]x^2 m
  Mat3 L = -0.5 * skew(m) + mu * w * theta.transpose();
  L += eta * (tm * Mat3::Identity() + theta * m.transpose() - 2.0 * m * theta.transpose());
  return L;
}

}  // namespace sutura::engine::so3
