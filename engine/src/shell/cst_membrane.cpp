#include "cst_membrane.hpp"

#include <algorithm>
#include <cmath>

namespace sutura::engine::dshell {

namespace {

// Mixed strain L = abar^-1 (a - abar) / 2 of the current corners.
Eigen::Matrix2d covariant_strain(const CstRest& r, const std::array<Vec3, 3>& x) {
  // Same metric routine as for abar, so a state equal to its rest gives exactly E = 0.
  return 0.5 * (triangle_metric(x[0], x[1], x[2]) - r.abar);
}

}  // namespace

Eigen::Matrix2d triangle_metric(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 d1 = p1 - p0;
  const Vec3 d2 = p2 - p0;
  const double a12 = d1.dot(d2);
  Eigen::Matrix2d a;
  a << d1.dot(d1), a12, a12, d2.dot(d2);
  return a;
}

CstRest make_cst_rest(const std::array<Vec3, 3>& X, const ShellMaterial& m) {
  CstRest r;
  r.abar = triangle_metric(X[0], X[1], X[2]);
  r.abar_inv = r.abar.inverse();
  r.area = 0.5 * std::sqrt(r.abar.determinant());  // det(abar) = |d1 x d2|^2 = (2A)^2
  const double E = m.youngs_modulus;
  const double nu = m.poisson_ratio;
  const double scale = r.area * m.thickness;
  r.lambda = scale * E * nu / (1.0 - nu * nu);
  r.mu = scale * E / (2.0 * (1.0 + nu));
  return r;
}

double cst_energy(const CstRest& r, const std::array<Vec3, 3>& x, Vec9* grad, Mat9* hess) {
  const Eigen::Matrix2d& M = r.abar_inv;
  const Eigen::Matrix2d E = covariant_strain(r, x);
  const Eigen::Matrix2d L = M * E;
  const double trL = L.trace();
  const double W = r.mu * (L * L).trace() + 0.5 * r.lambda * trL * trL;
  if (grad == nullptr) return W;

  // P = dW/dE = 2 mu M E M + lambda tr(L) M (symmetric). With dE = (dDi.Dj + Di.dDj)/2 the
  // gradient w.r.t. the edge vectors is dW/dd_i = sum_j P_ij d_j.
  Eigen::Matrix<double, 3, 2> Dm;
  Dm.col(0) = x[1] - x[0];
  Dm.col(1) = x[2] - x[0];
  Eigen::Matrix2d P = 2.0 * r.mu * M * E * M + r.lambda * trL * M;
  P = 0.5 * (P + P.transpose());
  const Eigen::Matrix<double, 3, 2> Gd = Dm * P;
  grad->segment<3>(0) = -(Gd.col(0) + Gd.col(1));
  grad->segment<3>(3) = Gd.col(0);
  grad->segment<3>(6) = Gd.col(1);
  if (hess == nullptr) return W;

  // d/dd_j of dW/dd_i, with q_i = sum_m M_mi d_m (columns of Q = Dm M):
  //   H_ij = P_ij I + lambda q_i q_j^T + mu q_j q_i^T + mu M_ij Dm M Dm^T
  // (derivation: dP = 2 mu M dE M + lambda tr(M dE) M, tr(M dE) = sum_n q_n . dd_n).
  const Eigen::Matrix<double, 3, 2> Q = Dm * M;
  const Eigen::Matrix3d DMD = Q * Dm.transpose();
  Eigen::Matrix3d Hd[2][2];
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      Hd[i][j] = P(i, j) * Eigen::Matrix3d::Identity() +
                 r.lambda * Q.col(i) * Q.col(j).transpose() +
                 r.mu * Q.col(j) * Q.col(i).transpose() + r.mu * M(i, j) * DMD;
    }
  }
  // Chain rule through d1 = x1 - x0, d2 = x2 - x0.
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) hess->block<3, 3>(3 + 3 * i, 3 + 3 * j) = Hd[i][j];
    const Eigen::Matrix3d row = -(Hd[i][0] + Hd[i][1]);
    hess->block<3, 3>(3 + 3 * i, 0) = row;
    hess->block<3, 3>(0, 3 + 3 * i) = row.transpose();
  }
  hess->block<3, 3>(0, 0) = Hd[0][0] + Hd[0][1] + Hd[1][0] + Hd[1][1];
  return W;
}

double cst_max_principal_strain(const CstRest& r, const std::array<Vec3, 3>& x) {
  // L is similar to a symmetric matrix, so its eigenvalues are real:
  // tr/2 +- sqrt(tr^2/4 - det).
  const Eigen::Matrix2d L = r.abar_inv * covariant_strain(r, x);
  const double half_tr = 0.5 * L.trace();
  return half_tr + std::sqrt(std::max(0.0, half_tr * half_tr - L.determinant()));
}

}  // namespace sutura::engine::dshell
