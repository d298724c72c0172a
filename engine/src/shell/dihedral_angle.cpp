#include "dihedral_angle.hpp"

#include <cmath>
#include <numbers>

#include "so3.hpp"

namespace sutura::engine::dshell {

namespace {

using Mat3x12 = Eigen::Matrix<double, 3, 12>;
using Row12 = Eigen::Matrix<double, 1, 12>;

using so3::skew;

// Jacobian of u = -|e| N / |N|^2 (the gradient of theta w.r.t. an apex), given dN/dx (3x12)
// and d|e|/dx (1x12): d(N/|N|^2) = (I - 2 n n^T) dN / |N|^2.
Mat3x12 apex_gradient_jacobian(const Vec3& N, double le, const Mat3x12& dN, const Row12& dle) {
  const double n2 = N.squaredNorm();
  const Vec3 n = N / std::sqrt(n2);
  const Eigen::Matrix3d proj = (Eigen::Matrix3d::Identity() - 2.0 * n * n.transpose()) / n2;
  return -((N / n2) * dle + le * proj * dN);
}

}  // namespace

double dihedral_angle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Vec12* grad,
                      Mat12* hess) {
  const Vec3 e = b - a;
  const Vec3 Nf = e.cross(c - a);
  const Vec3 Ng = (a - b).cross(d - b);
  const double le = e.norm();
  const double theta = std::atan2(Nf.cross(Ng).dot(e) / le, Nf.dot(Ng));
  if (grad == nullptr) return theta;

  const double le2 = le * le;
  const Vec3 gc = -le * Nf / Nf.squaredNorm();
  const Vec3 gd = -le * Ng / Ng.squaredNorm();
  const double tc = (c - a).dot(e) / le2;
  const double td = (d - a).dot(e) / le2;
  grad->segment<3>(0) = -(1.0 - tc) * gc - (1.0 - td) * gd;
  grad->segment<3>(3) = -tc * gc - td * gd;
  grad->segment<3>(6) = gc;
  grad->segment<3>(9) = gd;
  if (hess == nullptr) return theta;

  // dN_f: a -> [c-b]x, b -> -[c-a]x, c -> [b-a]x;  dN_g: a -> -[d-b]x, b -> [d-a]x, d -> [a-b]x.
  Mat3x12 dNf = Mat3x12::Zero();
  dNf.block<3, 3>(0, 0) = skew(c - b);
  dNf.block<3, 3>(0, 3) = -skew(c - a);
  dNf.block<3, 3>(0, 6) = skew(e);
  Mat3x12 dNg = Mat3x12::Zero();
  dNg.block<3, 3>(0, 0) = -skew(d - b);
  dNg.block<3, 3>(0, 3) = skew(d - a);
  dNg.block<3, 3>(0, 9) = -skew(e);
  const Vec3 eh = e / le;
  Row12 dle = Row12::Zero();
  dle.segment<3>(0) = -eh.transpose();
  dle.segment<3>(3) = eh.transpose();
  const Mat3x12 dgc = apex_gradient_jacobian(Nf, le, dNf, dle);
  const Mat3x12 dgd = apex_gradient_jacobian(Ng, le, dNg, dle);

  // t_p = (p - a).e / |e|^2:  dt/da = (2 t e - e - (p-a)) / |e|^2, dt/db = ((p-a) - 2 t e) / |e|^2,
  // dt/dp = e / |e|^2.
  auto projection_jacobian = [&](const Vec3& p, double t, int slot) {
    Row12 dt = Row12::Zero();
    dt.segment<3>(0) = ((2.0 * t - 1.0) * e - (p - a)).transpose() / le2;
    dt.segment<3>(3) = ((p - a) - 2.0 * t * e).transpose() / le2;
    dt.segment<3>(3 * slot) = e.transpose() / le2;
    return dt;
  };
  const Row12 dtc = projection_jacobian(c, tc, 2);
  const Row12 dtd = projection_jacobian(d, td, 3);

  Mat12& H = *hess;
  H.middleRows<3>(0) = -(1.0 - tc) * dgc + gc * dtc - (1.0 - td) * dgd + gd * dtd;
  H.middleRows<3>(3) = -tc * dgc - gc * dtc - td * dgd - gd * dtd;
  H.middleRows<3>(6) = dgc;
  H.middleRows<3>(9) = dgd;
  H = 0.5 * (H + H.transpose()).eval();
  return theta;
}

double rest_dihedral_angle(const ElementRest& f, int fa, int fb, const ElementRest& g, int ga,
                           int gb) {
  // Edge a -> b in each element's own rest frame (independent of the element's placement).
  const Vec3 ef = element_frame(f.X[0], f.X[1], f.X[2]).transpose() * (f.X[fb] - f.X[fa]);
  const Vec3 eg = element_frame(g.X[0], g.X[1], g.X[2]).transpose() * (g.X[gb] - g.X[ga]);
  // Q = T^T D, so a vector v in the element frame is Q^T v in the node frame.
  auto angle_at_node = [&](int kf, int kg) {
    const Quat qf = f.Q[kf].normalized().conjugate();
    const Quat qg = g.Q[kg].normalized().conjugate();
    const Vec3 nf = qf * Vec3::UnitZ();
    const Vec3 ng = qg * Vec3::UnitZ();
    const Vec3 axis = ((qf * ef).normalized() + (qg * eg).normalized()).normalized();
    return std::atan2(axis.dot(nf.cross(ng)), nf.dot(ng));
  };
  const double theta_a = angle_at_node(fa, ga);
  const double theta_b = angle_at_node(fb, gb);
  return theta_a + 0.5 * std::remainder(theta_b - theta_a, 2.0 * std::numbers::pi);
}

}  // namespace sutura::engine::dshell
