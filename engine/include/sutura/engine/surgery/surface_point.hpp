#pragma once
// Points on a mesh surface: the closest surface point to a point in space.
#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

struct SurfacePoint {
  FaceId face;
  Eigen::Vector3d bary;  ///< barycentric coordinates in `face` (corner order), sum 1
  Vec3 position;         ///< on the surface
  double distance = 0.0; ///< from the query point, mm
};

/// Closest point of the surface to `p` (ties: lowest face id). Brute force, O(F): meant for
/// the handful of points of an incision or a suture, not for per-frame picking.
/// Throws InvalidArgument on an empty mesh or a non-finite point.
SurfacePoint closest_surface_point(const SurfaceMesh& mesh, const Vec3& p);

/// Closest point on triangle (a, b, c) to p, as barycentric coordinates (Ericson, Real-Time
/// Collision Detection, 5.1.5).
Eigen::Vector3d closest_point_barycentric(const Vec3& p, const Vec3& a, const Vec3& b,
                                          const Vec3& c);

}  // namespace sutura::engine
