#include "sutura/engine/sim/area_barrier.hpp"

#include <cmath>
#include <limits>

#include "../shell/so3.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {
namespace {

using Mat3 = Eigen::Matrix3d;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using so3::skew;

}  // namespace

AreaBarrier::AreaBarrier(const ShellProblem& problem, const AreaBarrierParams& params)
    : problem_(problem), params_(params) {
  if (!(params.activation > 0.0 && params.activation < 1.0))
    throw InvalidArgument("area barrier: activation must be in (0, 1)");
  if (!(params.factor > 0.0 && std::isfinite(params.factor)))
    throw InvalidArgument("area barrier: factor must be finite and > 0");
}

double AreaBarrier::add_energy_gradient_hessian(const ShellState& s, int d, Eigen::VectorXd& g,
                                                Triplets* K) const {
  const double r0 = params_.activation;
  double energy = 0.0;
  for (std::size_t f = 0; f < problem_.faces->size(); ++f) {
    const FaceIndices& face = (*problem_.faces)[f];
    const double A0 = rest_area(problem_.rest->elements[f]);
    if (!(A0 > 0.0)) continue;
    const std::array<Vec3, 3> x = {s.x[face[0]], s.x[face[1]], s.x[face[2]]};
    const Vec3 n = (x[1] - x[0]).cross(x[2] - x[0]);
    const double nn = n.norm();
    const double A = 0.5 * nn;
    const double r = A / A0;
    if (r >= r0) continue;
    const ShellMaterial& m = (*problem_.materials)[(*problem_.face_material)[f]];
    const double k = params_.factor * m.youngs_modulus * m.thickness;
    if (!(r > 0.0)) {  // collapsed: the barrier is infinite
      energy = std::numeric_limits<double>::infinity();
      continue;
    }
    const double lr = std::log(r / r0), dr = r - r0;
    const double b = -dr * dr * lr;
    const double b1 = -2.0 * dr * lr - dr * dr / r;
    const double b2 = -2.0 * lr - 4.0 * dr / r + dr * dr / (r * r);
    energy += k * A0 * b;
    // dA/dx_i = 1/2 J_i^T n^ with J_i = dn/dx_i = [e_i]x, e_i = x_{i+2} - x_{i+1}.
    const Vec3 nh = n / nn;
    Eigen::Matrix<double, 3, 9> J;
    for (int i = 0; i < 3; ++i) J.block<3, 3>(0, 3 * i) = skew(x[(i + 2) % 3] - x[(i + 1) % 3]);
    const Vec9 gA = 0.5 * J.transpose() * nh;
    const Vec9 ge = k * b1 * gA;
    for (int i = 0; i < 3; ++i) g.segment<3>(static_cast<Eigen::Index>(d * face[i])) += ge.segment<3>(3 * i);
    if (K == nullptr) continue;
    // d2A = 1/2 (J^T (I - n^ n^T) J / |n| + N), N the constant second derivative of n
    // contracted with n^: blocks (i, i+1) = -[n^]x, (i, i+2) = +[n^]x.
    Mat9 N = Mat9::Zero();
    const Mat3 S = skew(nh);
    for (int i = 0; i < 3; ++i) {
      N.block<3, 3>(3 * i, 3 * ((i + 1) % 3)) = -S;
      N.block<3, 3>(3 * i, 3 * ((i + 2) % 3)) = S;
    }
    const Mat9 HA =
        0.5 * (J.transpose() * (Mat3::Identity() - nh * nh.transpose()) * J / nn + N);
    const Mat9 H = k * (b2 / A0 * gA * gA.transpose() + b1 * HA);
    for (int i = 0; i < 9; ++i)
      for (int j = 0; j < 9; ++j)
        K->emplace_back(d * face[i / 3] + i % 3, d * face[j / 3] + j % 3, H(i, j));
  }
  return energy;
}

}  // namespace sutura::engine
