#pragma once
// Tracing an incision curve over the surface: the sequence of "events" (existing vertices,
// edge crossings, face-interior points) the cut passes through, on the unrefined mesh.
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/surface_point.hpp"

namespace sutura::engine::detail {

struct PathEvent {
  enum class Kind { Vertex, Edge, Face } kind = Kind::Vertex;
  VertexId vertex;          ///< Vertex
  VertexId edge_a, edge_b;  ///< Edge: point (1 - t) a + t b
  double t = 0.0;
  FaceId face;              ///< Face: barycentric point
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  [[nodiscard]] bool same_as(const PathEvent& o) const;
};

/// The event for a curve point, with the sliver guard applied (corner or edge snapping).
PathEvent point_event(const SurfaceMesh& mesh, const SurfacePoint& p, double sliver);

/// Events strictly between p and q (excluding both ends) along the trace of the plane through
/// p and q containing the mean surface normal. Throws InvalidArgument when the trace reaches
/// the boundary or cannot be followed; `segment` (1-based) names the curve segment in messages.
std::vector<PathEvent> trace_between(const SurfaceMesh& mesh, const SurfacePoint& p,
                                     const PathEvent& pe, const SurfacePoint& q,
                                     const PathEvent& qe, double sliver, int segment);

/// Shortest edge path from a to b (Dijkstra on edge lengths), vertices from a to b inclusive.
/// Throws InvalidArgument when b is not reachable.
std::vector<VertexId> shortest_edge_path(const SurfaceMesh& mesh, VertexId a, VertexId b);

}  // namespace sutura::engine::detail
