#pragma once
// The rotation that best maps one set of edge vectors onto another (private to engine/src):
// the orthogonal Procrustes problem, solved by the polar decomposition of the covariance
// (Sorkine & Alexa 2007, as-rigid-as-possible; Mueller et al. 2005, shape matching).
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace sutura::engine::detail {

/// Given S = sum_k w_k a_k b_k^T (w_k >= 0), the rotation R (det +1) minimising
/// sum_k w_k |R a_k - b_k|^2. A planar set (rank-2 S, a vertex's one-ring on a surface) still
/// has one answer: the proper rotation also takes the plane's normal along. Where the best
/// orthogonal map is a reflection, the axis of the smallest singular value is flipped. S = 0
/// gives the identity. Cost: one 3x3 SVD (about a microsecond).
inline Eigen::Matrix3d best_rotation(const Eigen::Matrix3d& S) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  Eigen::Matrix3d R = svd.matrixV() * U.transpose();
  if (R.determinant() < 0.0) {
    U.col(2) *= -1.0;
    R = svd.matrixV() * U.transpose();
  }
  return R;
}

/// The same rotation by Newton's method from an estimate R (a rotation; the answer for a
/// nearby S, such as the last time step's). Why: where the estimate is close, two or three
/// iterations of about 150 flops each replace the SVD (a fifth of its time per node).
///
/// The rotation sought is the maximiser of tr(R^T A), A = S^T, over SO(3): there B = R^T A is
/// symmetric. With the answer written R exp([theta]x), B = exp([theta]x) P* for a symmetric
/// P*; linearised, with P = sym(B) for P*, (tr(P) I - P) theta = axial(B - B^T), since
/// [t]x P + P [t]x = [(tr(P) I - P) t]x for symmetric P. Of the stationary points of tr(R^T A) only the maximum
/// has tr(P) I - P positive definite (its eigenvalues are the sums of pairs of the signed
/// singular values), so a fixed point that passes that test is the answer, also where it is
/// the reflection-corrected one. Returns false when the iteration does not converge in 8
/// steps or meets a matrix that is not (clearly) positive definite, as at a saddle or for a
/// degenerate (rank < 2) S: then R is unspecified and best_rotation gives the answer.
inline bool refine_best_rotation(const Eigen::Matrix3d& S, Eigen::Matrix3d& R) {
  const Eigen::Matrix3d A = S.transpose();
  // Why a quaternion: each update is then exactly a rotation (normalised), however long a
  // chain of warm starts grows.
  Eigen::Quaterniond q(R);
  for (int it = 0; it < 8; ++it) {
    const Eigen::Matrix3d Rq = q.toRotationMatrix();
    const Eigen::Matrix3d B = Rq.transpose() * A;
    const Eigen::Matrix3d P = 0.5 * (B + B.transpose());
    Eigen::Matrix3d M = -P;
    M.diagonal().array() += P.trace();
    const Eigen::LLT<Eigen::Matrix3d> llt(M);
    // Positive definite with room: a pivot below 1e-10 of the scale is a rotation axis the
    // edges barely fix (a degenerate ring), left to the SVD.
    const double scale = B.cwiseAbs().maxCoeff();
    if (llt.info() != Eigen::Success || !(scale > 0.0) ||
        llt.matrixLLT().diagonal().minCoeff() <= 1e-5 * std::sqrt(scale))
      return false;
    const Eigen::Vector3d w(B(2, 1) - B(1, 2), B(0, 2) - B(2, 0), B(1, 0) - B(0, 1));
    const Eigen::Vector3d theta = llt.solve(w);
    const double angle = theta.norm();
    if (angle > 0.0) q = (q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, theta / angle))).normalized();
    // Quadratic convergence: past an update of 1e-8 rad the next would be round-off.
    if (angle <= 1e-8) {
      R = q.toRotationMatrix();
      return true;
    }
  }
  return false;
}

}  // namespace sutura::engine::detail
