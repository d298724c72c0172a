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

/// The event for a curve point: a corner when its barycentric coordinate is above
/// 1 - `snap`, an edge point when one coordinate is below `snap`, else a face point. (With a
/// tiny `snap` this only absorbs rounding; with a large one it is a sliver guard.)
PathEvent point_event(const SurfaceMesh& mesh, const SurfacePoint& p, double snap);

/// Faces of the (unrefined) mesh holding the event: a vertex's fan, an edge's one or two
/// faces, or the face.
std::vector<FaceId> event_faces(const SurfaceMesh& mesh, const PathEvent& e);

/// The event as barycentric coordinates of face f, which must hold it (see event_faces).
Eigen::Vector3d event_bary(const SurfaceMesh& mesh, const PathEvent& e, FaceId f);

/// Events strictly between p and q (excluding both ends) along the trace of the plane through
/// p and q containing the mean surface normal; a crossing within `snap` (fraction of the edge)
/// of an edge end is that vertex. Two consecutive events of the result (with pe before and qe
/// after) always lie in a common face of `mesh`. Throws InvalidArgument when the trace reaches
/// the boundary or cannot be followed; `segment` (1-based) names the curve segment in messages.
std::vector<PathEvent> trace_between(const SurfaceMesh& mesh, const SurfacePoint& p,
                                     const PathEvent& pe, const SurfacePoint& q,
                                     const PathEvent& qe, double snap, int segment);

/// Shortest edge path from a to b (Dijkstra on edge lengths), vertices from a to b inclusive.
/// Throws InvalidArgument when b is not reachable.
std::vector<VertexId> shortest_edge_path(const SurfaceMesh& mesh, VertexId a, VertexId b);

}  // namespace sutura::engine::detail
