// ANDES-OPT membrane triangle with drilling freedoms; see andes_membrane.hpp for the contract.
// Formulas from Felippa (2003), CMAME 192, 2125-2168 (ANDES template, OPT parameters).
#include "andes_membrane.hpp"

#include <algorithm>

#include <Eigen/LU>

#include "plane_stress.hpp"

namespace sutura::engine {

Eigen::Matrix<double, 9, 9> andes_membrane_stiffness(const std::array<Eigen::Vector2d, 3>& p,
                                                     const ShellMaterial& m) {
  using Mat3 = Eigen::Matrix3d;
  const double x1 = p[0].x(), x2 = p[1].x(), x3 = p[2].x();
  const double y1 = p[0].y(), y2 = p[1].y(), y3 = p[2].y();
  const double x12 = x1 - x2, x21 = -x12, x23 = x2 - x3, x32 = -x23, x31 = x3 - x1, x13 = -x31;
  const double y12 = y1 - y2, y21 = -y12, y23 = y2 - y3, y32 = -y23, y31 = y3 - y1, y13 = -y31;
  const double A = 0.5 * (x21 * y31 - x31 * y21);
  const double t = m.thickness;
  const double V = A * t;
  const Mat3 C = plane_stress_matrix(m);

  // Basic stiffness: force-lumping matrix L (without its factor t/2), alpha_b = 3/2.
  constexpr double ab = 1.5;
  Eigen::Matrix<double, 9, 3> L;
  L << y23, 0.0, x32,  //
      0.0, x32, y23,   //
      ab / 6 * y23 * (y13 - y21), ab / 6 * x32 * (x31 - x12), ab / 3 * (x31 * y13 - x12 * y21),
      y31, 0.0, x13,  //
      0.0, x13, y31,  //
      ab / 6 * y31 * (y21 - y32), ab / 6 * x13 * (x12 - x23), ab / 3 * (x12 * y21 - x23 * y32),
      y12, 0.0, x21,  //
      0.0, x21, y12,  //
      ab / 6 * y12 * (y32 - y13), ab / 6 * x21 * (x23 - x31), ab / 3 * (x23 * y32 - x31 * y13);
  // K_b = (t/2 L)(C)(t/2 L)^T / V. (lazyProduct: coefficient-based small products.)
  const Eigen::Matrix<double, 9, 3> LC = (t * t / (4.0 * V)) * L.lazyProduct(C);
  Eigen::Matrix<double, 9, 9> K = LC.lazyProduct(L.transpose());

  // Hierarchical rotations theta~_i = theta_i - omega, omega = 1/2 (dv/dx - du/dy):
  // theta~ = T_theta_u u.
  const double A4 = 4.0 * A;
  Eigen::Matrix<double, 3, 9> Ttu;
  for (int r = 0; r < 3; ++r) {
    Ttu.row(r) << x32, y32, 0.0, x13, y13, 0.0, x21, y21, 0.0;
    Ttu(r, 3 * r + 2) = A4;
  }
  Ttu /= A4;

  // Natural (side-direction) strains of sides 21, 32, 13 from Cartesian strains:
  // eps_side = [c^2, s^2, c s] . [eps_xx, eps_yy, gamma_xy]; T_e is the inverse map.
  const std::array<Eigen::Vector2d, 3> side = {p[1] - p[0], p[2] - p[1], p[0] - p[2]};
  const double l21 = side[0].squaredNorm(), l32 = side[1].squaredNorm(), l13 = side[2].squaredNorm();
  Mat3 S;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d d = side[k] / side[k].norm();
    S.row(k) << d.x() * d.x(), d.y() * d.y(), d.x() * d.y();
  }
  const Mat3 Te = S.inverse();
  const Mat3 Cn = Te.transpose() * C * Te;

  // Corner matrices Q1..Q3 of the optimal template (natural strains at the corners from
  // theta~), beta = (1, 2, 1, 0, 1, -1, -1, -1, -2).
  constexpr double b1 = 1, b2 = 2, b3 = 1, b4 = 0, b5 = 1, b6 = -1, b7 = -1, b8 = -1, b9 = -2;
  auto corner_matrix = [&](const double (&r)[9]) -> Mat3 {
    Mat3 Q;
    Q << r[0] / l21, r[1] / l21, r[2] / l21,  //
        r[3] / l32, r[4] / l32, r[5] / l32,   //
        r[6] / l13, r[7] / l13, r[8] / l13;
    return (2.0 * A / 3.0) * Q;
  };
  const Mat3 Q1 = corner_matrix({b1, b2, b3, b4, b5, b6, b7, b8, b9});
  const Mat3 Q2 = corner_matrix({b9, b7, b8, b3, b1, b2, b6, b4, b5});
  const Mat3 Q3 = corner_matrix({b5, b6, b4, b8, b9, b7, b2, b3, b1});
  // Side-midpoint values; the midpoint rule integrates the quadratic energy density exactly.
  const Mat3 Q4 = 0.5 * (Q1 + Q2), Q5 = 0.5 * (Q2 + Q3), Q6 = 0.5 * (Q3 + Q1);
  const double nu = m.poisson_ratio;
  // Floored at 0.01, reached at nu = kNearlyIncompressible (material.hpp warns above it).
  const double beta0 = std::max(0.5 * (1.0 - 4.0 * nu * nu), 0.01);
  Mat3 Ktheta = (0.75 * beta0 * V) *
                (Q4.transpose() * Cn * Q4 + Q5.transpose() * Cn * Q5 + Q6.transpose() * Cn * Q6);

  // Drilling penalty on the mean hierarchical rotation (see header): (1/3 sum theta~)^2.
  const double G = m.youngs_modulus / (2.0 * (1.0 + nu));
  Ktheta.array() += m.drilling_factor * G * t * A / 9.0;

  const Eigen::Matrix<double, 9, 3> TK = Ttu.transpose().lazyProduct(Ktheta);
  K.noalias() += TK.lazyProduct(Ttu);
  return K;
}

}  // namespace sutura::engine
