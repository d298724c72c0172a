#pragma once
// The rotation that best maps one set of edge vectors onto another (private to engine/src):
// the orthogonal Procrustes problem, solved by the polar decomposition of the covariance
// (Sorkine & Alexa 2007, as-rigid-as-possible; Mueller et al. 2005, shape matching).
#include <Eigen/Core>
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

}  // namespace sutura::engine::detail
