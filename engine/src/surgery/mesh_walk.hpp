#pragma once
// Small adjacency queries shared by the surgery edits.
#include "sutura/engine/mesh.hpp"

namespace sutura::engine::detail {

/// The half-edge u -> v, or an invalid id when u and v are not adjacent in that direction.
/// O(valence of u).
inline HalfedgeId find_halfedge(const SurfaceMesh& mesh, VertexId u, VertexId v) {
  for (const FaceId f : mesh.vertex_faces(u))
    for (int k = 0; k < 3; ++k) {
      const HalfedgeId h = SurfaceMesh::halfedge(f, k);
      if (mesh.from_vertex(h) == u && mesh.to_vertex(h) == v) return h;
    }
  return HalfedgeId();
}

}  // namespace sutura::engine::detail
