// DKT plate-bending triangle; see dkt_bending.hpp for the contract and conventions.
#include "dkt_bending.hpp"

#include "plane_stress.hpp"

namespace sutura::engine {
namespace {

using Mat29 = Eigen::Matrix<double, 2, 9>;

/// The 6-node quadratic interpolation of beta expressed in the 9 corner DOFs.
struct DktInterpolation {
  double area = 0.0;
  std::array<Eigen::Vector2d, 3> grad_l;  // gradients of the barycentric coordinates
  std::array<Mat29, 3> corner;            // beta at corner i
  std::array<Mat29, 3> mid;               // beta at the midpoint of the side opposite corner k
};

DktInterpolation make_interpolation(const std::array<Eigen::Vector2d, 3>& p) {
  DktInterpolation I;
  const double two_a = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) -
                       (p[2].x() - p[0].x()) * (p[1].y() - p[0].y());
  I.area = 0.5 * two_a;
  // beta = P theta: beta_x = theta_y, beta_y = -theta_x.
  Eigen::Matrix2d P;
  P << 0.0, 1.0, -1.0, 0.0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d& pj = p[(i + 1) % 3];
    const Eigen::Vector2d& pk = p[(i + 2) % 3];
    I.grad_l[i] = Eigen::Vector2d(pj.y() - pk.y(), pk.x() - pj.x()) / two_a;
    I.corner[i].setZero();
    I.corner[i].block<2, 2>(0, 3 * i + 1) = P;
  }
  for (int k = 0; k < 3; ++k) {
    // Side from corner i to corner j, opposite corner k.
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Eigen::Vector2d s = p[j] - p[i];
    const double len = s.norm();
    const Eigen::Vector2d tt = s / len;
    const Eigen::Vector2d nn(tt.y(), -tt.x());
    // Kirchhoff constraints at the side midpoint (cubic Hermite w along the side):
    // beta.t = -w'(mid) = -3/(2 len) (w_j - w_i) - 1/4 (beta_i + beta_j).t,
    // beta.n = 1/2 (beta_i + beta_j).n.
    const Eigen::Matrix2d Mk = 0.5 * nn * nn.transpose() - 0.25 * tt * tt.transpose();
    Mat29& B = I.mid[k];
    B.setZero();
    B.col(3 * i) = (1.5 / len) * tt;
    B.col(3 * j) = (-1.5 / len) * tt;
    B.block<2, 2>(0, 3 * i + 1) = Mk * P;
    B.block<2, 2>(0, 3 * j + 1) = Mk * P;
  }
  return I;
}

Eigen::Matrix<double, 3, 9> curvature_matrix(const DktInterpolation& I, const Eigen::Vector3d& L) {
  // Quadratic shape functions: corner N_i = L_i (2 L_i - 1), side (i, j): N = 4 L_i L_j.
  Mat29 dx = Mat29::Zero(), dy = Mat29::Zero();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d g = (4.0 * L[i] - 1.0) * I.grad_l[i];
    dx += g.x() * I.corner[i];
    dy += g.y() * I.corner[i];
  }
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Eigen::Vector2d g = 4.0 * (L[i] * I.grad_l[j] + L[j] * I.grad_l[i]);
    dx += g.x() * I.mid[k];
    dy += g.y() * I.mid[k];
  }
  Eigen::Matrix<double, 3, 9> B;
  B.row(0) = dx.row(0);
  B.row(1) = dy.row(1);
  B.row(2) = dy.row(0) + dx.row(1);
  return B;
}

/// The same at the midpoint of the side opposite corner k (L_k = 0, L_i = L_j = 1/2), where
/// the shape-function gradients reduce to: corners -grad L_k, grad L_i, grad L_j; side
/// midpoints -2 grad L_k (side k) and 2 grad L_k (sides i, j).
Eigen::Matrix<double, 3, 9> midpoint_curvature_matrix(const DktInterpolation& I, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const Mat29 Bk = 2.0 * (I.mid[i] + I.mid[j] - I.mid[k]) - I.corner[k];
  const Eigen::Vector2d& gk = I.grad_l[k];
  const Eigen::Vector2d& gi = I.grad_l[i];
  const Eigen::Vector2d& gj = I.grad_l[j];
  const Mat29 dx = gk.x() * Bk + gi.x() * I.corner[i] + gj.x() * I.corner[j];
  const Mat29 dy = gk.y() * Bk + gi.y() * I.corner[i] + gj.y() * I.corner[j];
  Eigen::Matrix<double, 3, 9> B;
  B.row(0) = dx.row(0);
  B.row(1) = dy.row(1);
  B.row(2) = dy.row(0) + dx.row(1);
  return B;
}

}  // namespace

Eigen::Matrix<double, 3, 9> dkt_curvature_matrix(const std::array<Eigen::Vector2d, 3>& p,
                                                 const Eigen::Vector3d& L) {
  return curvature_matrix(make_interpolation(p), L);
}

Eigen::Matrix<double, 9, 9> dkt_bending_stiffness(const std::array<Eigen::Vector2d, 3>& p,
                                                  const ShellMaterial& m) {
  const DktInterpolation I = make_interpolation(p);
  const double t = m.thickness;
  const Eigen::Matrix3d Db = (t * t * t / 12.0) * plane_stress_matrix(m);
  Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix<double, 3, 9> B = midpoint_curvature_matrix(I, k);
    const Eigen::Matrix<double, 9, 3> BD = (I.area / 3.0) * B.transpose().lazyProduct(Db);
    K.noalias() += BD.lazyProduct(B);
  }
  return K;
}

}  // namespace sutura::engine
