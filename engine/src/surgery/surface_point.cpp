#include "sutura/engine/surgery/surface_point.hpp"

#include <limits>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

Eigen::Vector3d closest_point_barycentric(const Vec3& p, const Vec3& a, const Vec3& b,
                                          const Vec3& c) {
  // Voronoi-region tests of Ericson's ClosestPtPointTriangle, returning barycentrics.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

SurfacePoint closest_surface_point(const SurfaceMesh& mesh, const Vec3& p) {
  if (mesh.empty()) throw InvalidArgument("closest_surface_point: the mesh has no faces");
  if (!p.allFinite()) throw InvalidArgument("closest_surface_point: the point is not finite");
  SurfacePoint best;
  best.distance = std::numeric_limits<double>::infinity();
  const auto& X = mesh.positions();
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const FaceIndices& t = mesh.faces()[f];
    const Eigen::Vector3d b = closest_point_barycentric(p, X[t[0]], X[t[1]], X[t[2]]);
    const Vec3 q = b[0] * X[t[0]] + b[1] * X[t[1]] + b[2] * X[t[2]];
    const double d = (q - p).norm();
    if (d < best.distance) {
      best = SurfacePoint{FaceId(f), b, q, d};
    }
  }
  return best;
}

}  // namespace sutura::engine
