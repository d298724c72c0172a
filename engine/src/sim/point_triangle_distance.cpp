#include "sutura/engine/sim/point_triangle_distance.hpp"

#include <array>
#include <cmath>

#include "jet.hpp"

namespace sutura::engine {

namespace {

using detail::Jet;
using detail::Jet3;

PointTriangleClosest make(TriangleFeature f, const Vec3& p, const std::array<const Vec3*, 3>& t,
                          const Eigen::Vector3d& w) {
  PointTriangleClosest c;
  c.feature = f;
  c.weights = w;
  c.point = w[0] * *t[0] + w[1] * *t[1] + w[2] * *t[2];
  c.squared_distance = (p - c.point).squaredNorm();
  return c;
}

// Nearest point of the three edges (the fallback for a degenerate triangle).
PointTriangleClosest nearest_edge(const Vec3& p, const std::array<const Vec3*, 3>& t) {
  static constexpr std::array<TriangleFeature, 3> kEdge = {TriangleFeature::Edge01,
                                                           TriangleFeature::Edge12,
                                                           TriangleFeature::Edge20};
  static constexpr std::array<TriangleFeature, 3> kVertex = {
      TriangleFeature::Vertex0, TriangleFeature::Vertex1, TriangleFeature::Vertex2};
  PointTriangleClosest best;
  best.squared_distance = HUGE_VAL;
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    const Vec3 e = *t[j] - *t[k];
    const double len2 = e.squaredNorm();
    const double s = len2 > 0.0 ? (p - *t[k]).dot(e) / len2 : 0.0;
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    PointTriangleClosest c;
    if (s <= 0.0) {
      w[k] = 1.0;
      c = make(kVertex[k], p, t, w);
    } else if (s >= 1.0) {
      w[j] = 1.0;
      c = make(kVertex[j], p, t, w);
    } else {
      w[k] = 1.0 - s, w[j] = s;
      c = make(kEdge[k], p, t, w);
    }
    if (c.squared_distance < best.squared_distance) best = c;
  }
  return best;
}

// Squared distance to the plane of the triangle, variables (p, t0, t1, t2).
Jet<12> face_jet(const Vec3& p, const Vec3& t0, const Vec3& t1, const Vec3& t2) {
  const Jet3<12> P = detail::variables<12>(p, 0), A = detail::variables<12>(t0, 3),
                 B = detail::variables<12>(t1, 6), C = detail::variables<12>(t2, 9);
  const Jet3<12> n = detail::cross(B - A, C - A);
  const Jet<12> rn = detail::dot(P - A, n);
  return (rn * rn) / detail::dot(n, n);
}

// Squared distance to the line through (a, b), variables (p, a, b).
Jet<9> edge_jet(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Jet3<9> P = detail::variables<9>(p, 0), A = detail::variables<9>(a, 3),
                B = detail::variables<9>(b, 6);
  const Jet3<9> e = B - A;
  const Jet3<9> c = detail::cross(P - A, e);
  return detail::dot(c, c) / detail::dot(e, e);
}

// Places the Hessian over M points (p and some corners) into the 12x12 (p, t0, t1, t2) layout;
// blocks[a] is the 3x3 block row of point a there.
template <int M>
void scatter(const Eigen::Matrix<double, 3 * M, 3 * M>& h, const std::array<int, M>& blocks,
             Mat12& out) {
  for (int a = 0; a < M; ++a)
    for (int b = 0; b < M; ++b)
      out.block<3, 3>(3 * blocks[a], 3 * blocks[b]) = h.template block<3, 3>(3 * a, 3 * b);
}

}  // namespace

PointTriangleClosest closest_point_on_triangle(const Vec3& p, const Vec3& t0, const Vec3& t1,
                                               const Vec3& t2) {
  const std::array<const Vec3*, 3> t = {&t0, &t1, &t2};
  const Vec3 ab = t1 - t0, ac = t2 - t0, ap = p - t0;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return make(TriangleFeature::Vertex0, p, t, {1, 0, 0});
  const Vec3 bp = p - t1;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return make(TriangleFeature::Vertex1, p, t, {0, 1, 0});
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return make(TriangleFeature::Edge01, p, t, {1.0 - v, v, 0.0});
  }
  const Vec3 cp = p - t2;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return make(TriangleFeature::Vertex2, p, t, {0, 0, 1});
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return make(TriangleFeature::Edge20, p, t, {1.0 - w, 0.0, w});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make(TriangleFeature::Edge12, p, t, {0.0, 1.0 - w, w});
  }
  // Interior: va + vb + vc = |ab x ac|^2 > 0 unless the triangle is degenerate.
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return nearest_edge(p, t);
  return make(TriangleFeature::Face, p, t, {va / sum, vb / sum, vc / sum});
}

PointTriangleDistance point_triangle_squared_distance(const Vec3& p, const Vec3& t0, const Vec3& t1,
                                                      const Vec3& t2, bool with_hessian) {
  PointTriangleDistance out;
  out.closest = closest_point_on_triangle(p, t0, t1, t2);
  const Vec3 r = p - out.closest.point;
  out.gradient.segment<3>(0) = 2.0 * r;
  for (int k = 0; k < 3; ++k) out.gradient.segment<3>(3 + 3 * k) = -2.0 * out.closest.weights[k] * r;
  if (!with_hessian) return out;

  const std::array<const Vec3*, 3> t = {&t0, &t1, &t2};
  const auto edge = [&](int i, int j) {
    scatter<3>(edge_jet(p, *t[i], *t[j]).h, {0, 1 + i, 1 + j}, out.hessian);
  };
  const auto vertex = [&](int i) {
    const Eigen::Matrix3d I2 = 2.0 * Eigen::Matrix3d::Identity();
    Eigen::Matrix<double, 6, 6> h;
    h << I2, -I2, -I2, I2;
    scatter<2>(h, {0, 1 + i}, out.hessian);
  };
  switch (out.closest.feature) {
    case TriangleFeature::Face: out.hessian = face_jet(p, t0, t1, t2).h; break;
    case TriangleFeature::Edge01: edge(0, 1); break;
    case TriangleFeature::Edge12: edge(1, 2); break;
    case TriangleFeature::Edge20: edge(2, 0); break;
    case TriangleFeature::Vertex0: vertex(0); break;
    case TriangleFeature::Vertex1: vertex(1); break;
    case TriangleFeature::Vertex2: vertex(2); break;
  }
  return out;
}

}  // namespace sutura::engine
