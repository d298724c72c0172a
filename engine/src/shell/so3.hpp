#pragma once
// Rotation-group helpers for the 6-DOF shells (private to the engine; also the skew matrix
// that the loads, the collapse barrier and the hinge bending share).
//
// Conventions: rotation vectors theta (rad), R = exp([theta]x). Left (spatial) perturbations:
// exp(theta + dtheta) = exp([J_l(theta) dtheta]x) exp(theta), hence for R <- exp([phi]x) R the
// rotation vector changes by dtheta = J_l^{-1}(theta) phi. J_l^{-1} is the matrix called H
// in Felippa & Haugen (2005), "A unified formulation of small-strain corotational finite
// elements: I. Theory", CMAME 194 (rotation-vector Jacobian). Everything here is exact
// (no small-rotation approximation); series expansions, accurate to round-off, replace the
// closed forms where those lose precision (|theta| < 0.25) and, in log_quat, where they cost
// more (angles below 11.4 deg).
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
  const double s2 = v.squaredNorm();
  const double w = q.w();
  // theta = k v with k = 2 atan2(s, w) / s = (2/w) atan(z)/z, z = s/w. Below z = 0.1 (angles
  // under 11.4 deg: the corotated element rotations) the alternating series
  // atan(z)/z = sum_n (-1)^n z^2n / (2n + 1) to z^16 is exact to z^18/19 < 6e-20 and costs a
  // third of atan2 (the gradient evaluates three per element).
  if (s2 < 0.01 * w * w) {
    const double z2 = s2 / (w * w);
    const double series =
        1.0 + z2 * (-1.0 / 3.0 + z2 * (1.0 / 5.0 + z2 * (-1.0 / 7.0 + z2 * (1.0 / 9.0 +
        z2 * (-1.0 / 11.0 + z2 * (1.0 / 13.0 + z2 * (-1.0 / 15.0 + z2 / 17.0)))))));
    return (2.0 / w * series) * v;
  }
  const double s = std::sqrt(s2);
  return (2.0 * std::atan2(s, w) / s) * v;
}

/// eta(t) = (1 - (t/2) cot(t/2)) / t^2 and mu(t) = eta'(t)/t, t = |theta|: the scalar
/// functions of J_l^{-1} and of its derivative.
struct InverseJacobianScalars {
  double eta;
  double mu;
};

/// eta(t) alone (what J_l^{-1} needs; the gradient evaluates three per element).
inline double inverse_jacobian_eta(double t) {
  const double t2 = t * t;
  if (t < 0.25) {
    // (t/2) cot(t/2) = 1 - t^2/12 - t^4/720 - t^6/30240 - t^8/1209600 - t^10/47900160 - ...;
    // truncation error below 1e-10 relative here, where the closed forms lose up to 1e-7.
    return 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0 + t2 * t2 * t2 / 1209600.0 +
           t2 * t2 * t2 * t2 / 47900160.0;
  }
  // (t/2) cot(t/2) = t (1 + c) / (2 s) = t s / (2 (1 - c)); the second form stays finite at t = pi.
  return 1.0 / t2 - std::sin(t) / (2.0 * t * (1.0 - std::cos(t)));
}

inline InverseJacobianScalars inverse_jacobian_scalars(double t) {
  const double t2 = t * t;
  const double eta = inverse_jacobian_eta(t);
  if (t < 0.25)
    return {eta, 1.0 / 360.0 + t2 / 7560.0 + t2 * t2 / 201600.0 + t2 * t2 * t2 / 5987520.0};
  const double s = std::sin(t);
  const double c = std::cos(t);
  // eta' = -2/t^3 + 1/(2t) + (s + t c) / (2 t^2 (1 - c))  (quotient rule, (1+c)/s^2 = 1/(1-c)).
  const double deta = -2.0 / (t2 * t) + 1.0 / (2.0 * t) + (s + t * c) / (2.0 * t2 * (1.0 - c));
  return {eta, deta / t};
}

/// J_l^{-1}(theta) = I - 1/2 [theta]x + eta [theta]x^2, with [theta]x^2 = theta theta^T - t^2 I.
inline Mat3 left_jacobian_inverse(const Vec3& theta) {
  const double t2 = theta.squaredNorm();
  const double eta = inverse_jacobian_eta(std::sqrt(t2));
  Mat3 H = eta * theta * theta.transpose();
  H.diagonal().array() += 1.0 - eta * t2;
  const Vec3 h = 0.5 * theta;
  H(0, 1) += h.z();
  H(0, 2) -= h.y();
  H(1, 0) -= h.z();
  H(1, 2) += h.x();
  H(2, 0) += h.y();
  H(2, 1) -= h.x();
  return H;
}

/// J_l^{-T}(theta) m = m + 1/2 theta x m + eta (theta (theta.m) - t^2 m), without forming the
/// matrix (the gradient needs only this product).
inline Vec3 left_jacobian_inverse_transpose_times(const Vec3& theta, const Vec3& m) {
  const double t2 = theta.squaredNorm();
  const double eta = inverse_jacobian_eta(std::sqrt(t2));
  return m + 0.5 * theta.cross(m) + eta * (theta.dot(m) * theta - t2 * m);
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
