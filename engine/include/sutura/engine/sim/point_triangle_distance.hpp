#pragma once
// Distance from a point to a triangle with derivatives, for contact (IPC style: the distance
// is taken to the closest feature, and within a feature's region it is a smooth function).
//
// Regions: the closest point lies in the triangle's interior (Face), on an edge (Edge01 =
// corners 0-1, Edge12, Edge20) or at a corner (Vertex0..2). In each region the squared
// distance b is the smooth function of that feature:
//   Face:   b = ((p - t0) . n)^2 / (n . n),           n = (t1 - t0) x (t2 - t0)
//   Edge:   b = |(p - ti) x (tj - ti)|^2 / |tj - ti|^2
//   Vertex: b = |p - ti|^2
// b is C1 across region boundaries (its gradient 2 (p - c) is continuous) but its Hessian
// jumps there.
#include <Eigen/Core>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

enum class TriangleFeature { Face, Edge01, Edge12, Edge20, Vertex0, Vertex1, Vertex2 };

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

struct PointTriangleClosest {
  TriangleFeature feature = TriangleFeature::Face;
  Vec3 point = Vec3::Zero();                 ///< closest point on the triangle
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  ///< barycentric weights of `point`
  double squared_distance = 0.0;
};

/// Closest point of the triangle (t0, t1, t2) to p by Voronoi-region classification (Ericson,
/// Real-Time Collision Detection, 5.1.5). A degenerate (zero-area) triangle is handled as its
/// nearest edge. O(1).
PointTriangleClosest closest_point_on_triangle(const Vec3& p, const Vec3& t0, const Vec3& t1,
                                               const Vec3& t2);

struct PointTriangleDistance {
  PointTriangleClosest closest;
  /// d b / d(p, t0, t1, t2) (12 entries, 3 per point). By the envelope theorem
  /// d b/dp = 2 (p - c) and d b/dt_k = -2 w_k (p - c), with c the closest point, w its weights.
  Vec12 gradient = Vec12::Zero();
  /// Hessian of the region's smooth b (exact second derivatives by forward-mode automatic
  /// differentiation); zero unless requested.
  Mat12 hessian = Mat12::Zero();
};

/// Squared distance, gradient and (with `with_hessian`) Hessian w.r.t. (p, t0, t1, t2).
/// Cost: O(1); about 10^4 flops with the Hessian in the face region.
PointTriangleDistance point_triangle_squared_distance(const Vec3& p, const Vec3& t0, const Vec3& t1,
                                                      const Vec3& t2, bool with_hessian);

}  // namespace sutura::engine
