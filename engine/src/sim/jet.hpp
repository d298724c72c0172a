#pragma once
// Second-order forward-mode automatic differentiation (internal): a Jet carries a value with
// its gradient and Hessian w.r.t. N variables, and arithmetic propagates them exactly
// (product rule: H(ab) = a Hb + b Ha + ga gb^T + gb ga^T). Used for the few small rational
// functions whose hand-derived Hessians would be long and error-prone (contact distances).
#include <array>

#include <Eigen/Core>

namespace sutura::engine::detail {

template <int N>
struct Jet {
  double v = 0.0;
  Eigen::Matrix<double, N, 1> g = Eigen::Matrix<double, N, 1>::Zero();
  Eigen::Matrix<double, N, N> h = Eigen::Matrix<double, N, N>::Zero();

  static Jet variable(double value, int index) {
    Jet j;
    j.v = value;
    j.g[index] = 1.0;
    return j;
  }
};

template <int N>
Jet<N> operator+(const Jet<N>& a, const Jet<N>& b) {
  return {a.v + b.v, a.g + b.g, a.h + b.h};
}
template <int N>
Jet<N> operator-(const Jet<N>& a, const Jet<N>& b) {
  return {a.v - b.v, a.g - b.g, a.h - b.h};
}
template <int N>
Jet<N> operator*(const Jet<N>& a, const Jet<N>& b) {
  const Eigen::Matrix<double, N, N> outer = a.g * b.g.transpose();
  return {a.v * b.v, a.v * b.g + b.v * a.g, a.v * b.h + b.v * a.h + outer + outer.transpose()};
}
// q = a / b from a = q b: gq = (ga - q gb) / b, Hq = (Ha - q Hb - gq gb^T - gb gq^T) / b.
template <int N>
Jet<N> operator/(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> q;
  q.v = a.v / b.v;
  q.g = (a.g - q.v * b.g) / b.v;
  const Eigen::Matrix<double, N, N> outer = q.g * b.g.transpose();
  q.h = (a.h - q.v * b.h - outer - outer.transpose()) / b.v;
  return q;
}

template <int N>
using Jet3 = std::array<Jet<N>, 3>;

/// The point's coordinates as variables first, first + 1, first + 2.
template <int N>
Jet3<N> variables(const Eigen::Vector3d& x, int first) {
  return {Jet<N>::variable(x.x(), first), Jet<N>::variable(x.y(), first + 1),
          Jet<N>::variable(x.z(), first + 2)};
}
template <int N>
Jet3<N> operator-(const Jet3<N>& a, const Jet3<N>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <int N>
Jet<N> dot(const Jet3<N>& a, const Jet3<N>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <int N>
Jet3<N> cross(const Jet3<N>& a, const Jet3<N>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace sutura::engine::detail
