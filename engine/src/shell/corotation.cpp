// EICR kinematics, gradient and consistent tangent; derivation summarised in corotation.hpp.
#include "corotation.hpp"

#include <cmath>

#include "so3.hpp"

namespace sutura::engine {
namespace {

using Mat3 = Eigen::Matrix3d;
using so3::skew;

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

LocalRest make_local_rest(const ElementRest& rest) {
  LocalRest r;
  const Eigen::Vector3d c = (rest.X[0] + rest.X[1] + rest.X[2]) / 3.0;
  const Mat3 T0 = element_frame(rest.X[0], rest.X[1], rest.X[2]);
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d v = T0.transpose() * (rest.X[a] - c);
    r.X[a] = v.head<2>();
    r.Q[a] = rest.Q[a];
  }
  r.area = 0.5 * cross2(r.X[1] - r.X[0], r.X[2] - r.X[0]);
  return r;
}

CorotatedElement corotate(const LocalRest& rest, const std::array<Eigen::Vector3d, 3>& x,
                          const std::array<Quat, 3>& D) {
  CorotatedElement e;
  const Eigen::Vector3d c = (x[0] + x[1] + x[2]) / 3.0;
  const Eigen::Vector3d a = x[1] - x[0];
  const Eigen::Vector3d e3 = a.cross(x[2] - x[0]).normalized();
  const Eigen::Vector3d e1a = a.normalized();
  const Eigen::Vector3d e2a = e3.cross(e1a);
  // Corner coordinates in the auxiliary edge-aligned frame, then the in-plane rotation psi
  // that best fits them to the rest coordinates: tan psi = sum X x p / sum X . p.
  std::array<Eigen::Vector2d, 3> p;
  double dot_sum = 0.0, cross_sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d r = x[k] - c;
    p[k] = {r.dot(e1a), r.dot(e2a)};
    dot_sum += rest.X[k].dot(p[k]);
    cross_sum += cross2(rest.X[k], p[k]);
  }
  const double len = std::sqrt(dot_sum * dot_sum + cross_sum * cross_sum);  // mm^2: no overflow
  const double cs = dot_sum / len, sn = cross_sum / len;
  e.T.col(0) = cs * e1a + sn * e2a;
  e.T.col(1) = -sn * e1a + cs * e2a;
  e.T.col(2) = e3;
  const Quat qT_inv = Quat(e.T).conjugate();
  for (int k = 0; k < 3; ++k) {
    e.x[k] = {cs * p[k].x() + sn * p[k].y(), -sn * p[k].x() + cs * p[k].y()};
    const Eigen::Vector3d theta = so3::log_quat(qT_inv * D[k] * rest.Q[k].conjugate());
    e.dm.segment<2>(3 * k) = e.x[k] - rest.X[k];
    e.dm(3 * k + 2) = theta.z();
    e.db.segment<2>(2 * k) = theta.head<2>();
  }
  return e;
}

void corotational_gradient(const LocalRest& rest, const CorotatedElement& e,
                           const LocalStiffness& K, const LocalForces& f, Vec18& g,
                           Mat18* tangent, bool symmetric) {
  const auto& X = rest.X;
  const auto& x = e.x;
  // Spin-fitter G_a (3x3 per corner, acting on xi_a): rows 0, 1 = tilt of the normal (slopes
  // of the plane through the displaced corners: G_a = [[0, 0, dN_a/dy], [0, 0, -dN_a/dx], .]),
  // row 2 = best-fit in-plane spin (-X_a,y / s, X_a,x / s, 0), s = sum_b X_b . x_b.
  const double two_a = cross2(x[1] - x[0], x[2] - x[0]);
  const double s = X[0].dot(x[0]) + X[1].dot(x[1]) + X[2].dot(x[2]);
  std::array<Eigen::Vector2d, 3> grad_n;  // gradients of the linear shape functions
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector2d& pb = x[(a + 1) % 3];
    const Eigen::Vector2d& pc = x[(a + 2) % 3];
    grad_n[a] = Eigen::Vector2d(pb.y() - pc.y(), pc.x() - pb.x()) / two_a;
  }

  // Corner forces n_a (in-plane; the normal shear forces drop out, see header) and moments m_a.
  std::array<Eigen::Vector3d, 3> n, m, mt, theta;
  Eigen::Vector3d nbar = Eigen::Vector3d::Zero();
  Eigen::Vector3d M = Eigen::Vector3d::Zero();  // moment conjugate to the frame spin
  for (int a = 0; a < 3; ++a) {
    n[a] = {f.fm(3 * a), f.fm(3 * a + 1), 0.0};
    m[a] = {f.fb(2 * a), f.fb(2 * a + 1), f.fm(3 * a + 2)};
    theta[a] = {e.db(2 * a), e.db(2 * a + 1), e.dm(3 * a + 2)};
    mt[a] = so3::left_jacobian_inverse_transpose_times(theta[a], m[a]);  // H_a^T m_a
    nbar += n[a] / 3.0;
    M.z() -= cross2(x[a], n[a].head<2>());
    M -= mt[a];
  }
  Vec18 gl;  // gradient in local components: P^T H^T f
  for (int a = 0; a < 3; ++a) {
    // G_a^T M with the structure of G_a spelled out.
    const Eigen::Vector3d GtM(-X[a].y() * M.z() / s, X[a].x() * M.z() / s,
                              grad_n[a].y() * M.x() - grad_n[a].x() * M.y());
    gl.segment<3>(6 * a) = n[a] - nbar + GtM;
    gl.segment<3>(6 * a + 3) = mt[a];
  }
  for (int b = 0; b < 6; ++b) g.segment<3>(3 * b) = e.T * gl.segment<3>(3 * b);
  if (tangent == nullptr) return;

  std::array<Mat3, 3> G, H;
  for (int a = 0; a < 3; ++a) {
    G[a] << 0.0, 0.0, grad_n[a].y(),  //
        0.0, 0.0, -grad_n[a].x(),     //
        -X[a].y() / s, X[a].x() / s, 0.0;
    H[a] = so3::left_jacobian_inverse(theta[a]);
  }

  // The tangent is built transposed, Kt^T, column by column (column-major storage: every
  // update below is a contiguous, vectorised column operation). B = d(d)/d(xi, eta) is held
  // as B^T, split into the columns of the membrane DOFs (u_x, u_y, theta_z per corner) and of
  // the bending DOFs (theta_x, theta_y per corner):
  //   du_a = xi_a - mean(xi) + x_a x (G xi),   dtheta_a = H_a (eta_a - G xi).
  using Mat18x9 = Eigen::Matrix<double, 18, 9>;
  using Mat18x6 = Eigen::Matrix<double, 18, 6>;
  using Mat18x3 = Eigen::Matrix<double, 18, 3>;
  using Col18 = Eigen::Matrix<double, 18, 1>;
  // G^T stacked over the 18 increments (zero rows for the spins).
  Mat18x3 GT = Mat18x3::Zero();
  for (int b = 0; b < 3; ++b) GT.middleRows<3>(6 * b) = G[b].transpose();
  Mat18x9 BmT = Mat18x9::Zero();
  Mat18x6 BbT;
  std::array<Mat18x3, 3> BtT;  // dtheta_a columns
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      // x_a x (G_b xi_b): in-plane part (y_a, -x_a) * (row 2 of G_b) xi_b.
      const double d = (a == b ? 1.0 : 0.0) - 1.0 / 3.0;
      BmT(6 * b, 3 * a) = d + x[a].y() * G[b](2, 0);
      BmT(6 * b + 1, 3 * a) = x[a].y() * G[b](2, 1);
      BmT(6 * b, 3 * a + 1) = -x[a].x() * G[b](2, 0);
      BmT(6 * b + 1, 3 * a + 1) = d - x[a].x() * G[b](2, 1);
    }
    BtT[a].noalias() = -GT.lazyProduct(H[a].transpose());
    BtT[a].middleRows<3>(6 * a + 3) = H[a].transpose();
    BmT.col(3 * a + 2) = BtT[a].col(2);
    BbT.middleCols<2>(2 * a) = BtT[a].leftCols<2>();
  }
  // Material part P^T H^T K H P = B^T K B (K symmetric): Kt = B^T (B^T K)^T.
  const Mat18x9 CmT = BmT.lazyProduct(K.membrane);
  const Mat18x6 CbT = BbT.lazyProduct(K.bending);
  Mat18 KtT = BmT.lazyProduct(CmT.transpose());
  KtT.noalias() += BbT.lazyProduct(CbT.transpose());

  // K_GR: the gradient is carried by the rotating frame, d(T gl) = T (domega x gl + d gl),
  // i.e. the rows 3a of Kt get -[gl_a]x G: the columns 3a of Kt^T get G^T [gl_a]x.
  for (int a = 0; a < 6; ++a)
    KtT.middleCols<3>(3 * a).noalias() += GT.lazyProduct(skew(gl.segment<3>(3 * a)));
  // K_M (variation of H_c^T m_c at fixed m_c) and the part of K_GP from the variation of the
  // corner positions in M = -sum x_c x n_c - sum H_c^T m_c:
  // d(gl_xi_a) += G_a^T W, d(gl_eta_c) += L_c dtheta_c, W = sum_c (n_c x du_c - L_c dtheta_c).
  Mat18x3 WT = Mat18x3::Zero();
  for (int c = 0; c < 3; ++c) {
    const Mat3 Lc = so3::d_left_jacobian_inverse_transpose(theta[c], m[c]);
    const Mat18x3 VT = BtT[c].lazyProduct(Lc.transpose());
    KtT.middleCols<3>(6 * c + 3) += VT;
    WT -= VT;
    // n_c x du_c with both in-plane: only the normal component.
    WT.col(2) += n[c].x() * BmT.col(3 * c + 1) - n[c].y() * BmT.col(3 * c);
  }
  // K_GP from the variation of G itself, through the current coordinates x (dx_b = du_b):
  // G_a^T M = (-X_a,y M_z / s, X_a,x M_z / s, h_a) with h_a = (M_x, M_y).(x_{a+2} - x_{a+1})/(2A).
  Col18 rX = Col18::Zero(), rN = Col18::Zero();  // sum_b X_b . du_b, sum_b grad N_b . du_b
  std::array<Col18, 3> rM;                         // (M_x, M_y) . du_b
  for (int b = 0; b < 3; ++b) {
    const auto dux = BmT.col(3 * b), duy = BmT.col(3 * b + 1);
    rX += X[b].x() * dux + X[b].y() * duy;
    rN += grad_n[b].x() * dux + grad_n[b].y() * duy;
    rM[b] = M.x() * dux + M.y() * duy;
  }
  const double mz_s2 = M.z() / (s * s);
  for (int a = 0; a < 3; ++a) {
    const double h = grad_n[a].y() * M.x() - grad_n[a].x() * M.y();
    // G_a^T W (structure of G_a spelled out).
    KtT.col(6 * a) += G[a](2, 0) * WT.col(2) + mz_s2 * X[a].y() * rX;
    KtT.col(6 * a + 1) += G[a](2, 1) * WT.col(2) - mz_s2 * X[a].x() * rX;
    KtT.col(6 * a + 2) += G[a](0, 2) * WT.col(0) + G[a](1, 2) * WT.col(1) +
                          (rM[(a + 2) % 3] - rM[(a + 1) % 3]) / two_a - h * rN;
  }
  if (symmetric) KtT = (0.5 * (KtT + KtT.transpose())).eval();

  // Back to global components: tangent = Tb Kt Tb^T with Tb = diag(T, ..., T), computed as
  // (Kt^T Tb^T)^T Tb^T in two passes of column-block products.
  const Mat3 Tt = e.T.transpose();
  Mat18 A;
  for (int j = 0; j < 6; ++j) A.middleCols<3>(3 * j).noalias() = KtT.middleCols<3>(3 * j).lazyProduct(Tt);
  KtT = A.transpose();
  for (int j = 0; j < 6; ++j)
    tangent->middleCols<3>(3 * j).noalias() = KtT.middleCols<3>(3 * j).lazyProduct(Tt);
}

}  // namespace sutura::engine
