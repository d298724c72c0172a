#include "hinge_bending.hpp"

#include <algorithm>
#include <cmath>

namespace sutura::engine::dshell {

FaceBending make_face_bending(const std::array<Vec3, 3>& X, const ShellMaterial& m,
                              const std::array<bool, 3>& interior) {
  std::array<Vec3, 3> e;
  Eigen::Vector3d len;
  for (int k = 0; k < 3; ++k) {
    e[k] = X[(k + 1) % 3] - X[k];
    len[k] = e[k].norm();
  }
  const double area = 0.5 * e[0].cross(e[1]).norm();
  const double nu = m.poisson_ratio;
  const double t = m.thickness;
  const double D = m.youngs_modulus * t * t * t / (12.0 * (1.0 - nu * nu));

  FaceBending fb;
  Eigen::Matrix3d C;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double c = e[i].dot(e[j]) / (len[i] * len[j]);
      fb.cos2(i, j) = c * c;
      C(i, j) = D / (4.0 * area) * len[i] * len[j] * (nu + (1.0 - nu) * c * c);
    }
  }
  fb.inv_height = len / (2.0 * area);

  // Minimiser over the boundary entries: solve rows b of C dtheta = 0 with the interior entries
  // prescribed (identity rows), then drop the boundary columns. S = P^T C P is the Schur
  // complement; without boundary edges P = I and S = C exactly.
  Eigen::Matrix3d A = C;
  for (int k = 0; k < 3; ++k) {
    if (interior[k]) A.row(k) = Eigen::RowVector3d::Unit(k);
  }
  fb.P = A.inverse();
  for (int k = 0; k < 3; ++k) {
    if (!interior[k]) fb.P.col(k).setZero();
  }
  fb.S = fb.P.transpose() * C * fb.P;
  return fb;
}

double max_curvature_change(const FaceBending& b, const Eigen::Vector3d& dtheta) {
  // K = sum_k kappa_k b_k b_k^T with kappa_k = dtheta_k / h_k; for a symmetric 2x2 K,
  // eigenvalues = tr/2 +- sqrt(2 tr(K^2) - tr^2)/2 with tr(K^2) = kappa^T cos2 kappa.
  const Eigen::Vector3d kappa = (b.P * dtheta).cwiseProduct(b.inv_height);
  const double tr = kappa.sum();
  const double tr_sq = kappa.dot(b.cos2 * kappa);
  return 0.5 * std::abs(tr) + 0.5 * std::sqrt(std::max(0.0, 2.0 * tr_sq - tr * tr));
}

}  // namespace sutura::engine::dshell
